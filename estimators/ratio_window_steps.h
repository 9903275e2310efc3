#pragma once
// The inner loop of identification's R(n) = MVAR(m) / OAVAR(m) from the integrated record
// (noise_identification.cc): the window w of the last m Allan differences a_u, carried four
// steps at a time. Step group g reads, for l < 4 and i = 4 g + l, the record at u - m, u, u + m
// and u + 2m through x0[i], x1[i], x2[i], x3[i] (u the step's incoming term), and does
//   in_l = (x3 - x2) - (x2 - x1), trail_l = (x2 - x1) - (x1 - x0), d_l = in_l - trail_l,
//   s_0 += w^2, s_1 += (w + d_0)^2, s_2 += (w + (d_0 + d_1))^2, s_3 += (w + ((d_0 + d_1) + d_2))^2,
//   q_l += in_l^2, w += (d_0 + d_1) + (d_2 + d_3).
// The AVX2 version computes the four steps of a group in the four lanes of a register with the
// same operations in the same order (no fused multiply-add: this file is compiled with
// -ffp-contract=off), so its results are bit-identical to the portable one.
#include <cstdint>

namespace allanlab::estimators {

enum class RatioStepsKernel { kBest, kAvx2, kPortable };

// True when this CPU runs `kernel` (always for kBest and kPortable).
bool RatioStepsKernelRuns(RatioStepsKernel kernel);

// `groups` step groups from the window `window`; s[0..3] and q[0..3] accumulate. Returns the window
// after them. A kernel this CPU does not run falls back on the portable code.
double RatioWindowSteps(const double* x0, const double* x1, const double* x2, const double* x3, std::int64_t groups,
                        double window, double* s, double* q, RatioStepsKernel kernel = RatioStepsKernel::kBest);

}  // namespace allanlab::estimators
