#include "estimators/ratio_window_steps.h"

#include "common/cpu_features.h"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define ALLANLAB_HAVE_AVX2_RATIO 1
#endif

namespace allanlab::estimators {
namespace {

double PortableSteps(const double* x0, const double* x1, const double* x2, const double* x3, std::int64_t groups,
                     double window, double* s, double* q) {
  double s0 = s[0], s1 = s[1], s2 = s[2], s3 = s[3];
  double q0 = q[0], q1 = q[1], q2 = q[2], q3 = q[3];
  auto lead = [&](std::int64_t i) { return (x3[i] - x2[i]) - (x2[i] - x1[i]); };
  auto trail = [&](std::int64_t i) { return (x2[i] - x1[i]) - (x1[i] - x0[i]); };
  for (std::int64_t i = 0; i < 4 * groups; i += 4) {
    const double in0 = lead(i), in1 = lead(i + 1), in2 = lead(i + 2), in3 = lead(i + 3);
    const double d0 = in0 - trail(i), d1 = in1 - trail(i + 1);
    const double d2 = in2 - trail(i + 2), d3 = in3 - trail(i + 3);
    const double w1 = window + d0, w2 = window + (d0 + d1), w3 = window + ((d0 + d1) + d2);
    s0 += window * window;
    s1 += w1 * w1;
    s2 += w2 * w2;
    s3 += w3 * w3;
    q0 += in0 * in0;
    q1 += in1 * in1;
    q2 += in2 * in2;
    q3 += in3 * in3;
    window += ((d0 + d1) + (d2 + d3));
  }
  s[0] = s0, s[1] = s1, s[2] = s2, s[3] = s3;
  q[0] = q0, q[1] = q1, q[2] = q2, q[3] = q3;
  return window;
}

#ifdef ALLANLAB_HAVE_AVX2_RATIO
// Lane l holds step l of the group. The partial sums of the changes come from lane moves and
// additions of the same pairs: lanes (0, d0, d0 + d1, (d0 + d1) + d2) are (0, d0, e01, e01) + (0, 0,
// 0, d2) with e01 = d0 + d1 (a sum with 0 is exact, and its sign of zero is lost in the square
// below), and the window's change e01 + e23 is in every lane (x + y and y + x are the same
// number), so the window stays a broadcast and never leaves the register.
__attribute__((target("avx2"))) double Avx2Steps(const double* x0, const double* x1, const double* x2,
                                                 const double* x3, std::int64_t groups, double window, double* s,
                                                 double* q) {
  __m256d sums = _mm256_loadu_pd(s);
  __m256d squares = _mm256_loadu_pd(q);
  __m256d w = _mm256_set1_pd(window);
  const __m256d zero = _mm256_setzero_pd();
  for (std::int64_t i = 0; i < 4 * groups; i += 4) {
    const __m256d v0 = _mm256_loadu_pd(x0 + i), v1 = _mm256_loadu_pd(x1 + i);
    const __m256d v2 = _mm256_loadu_pd(x2 + i), v3 = _mm256_loadu_pd(x3 + i);
    const __m256d middle = _mm256_sub_pd(v2, v1);
    const __m256d in = _mm256_sub_pd(_mm256_sub_pd(v3, v2), middle);
    const __m256d trail = _mm256_sub_pd(middle, _mm256_sub_pd(v1, v0));
    const __m256d d = _mm256_sub_pd(in, trail);
    const __m256d pairs = _mm256_add_pd(d, _mm256_permute_pd(d, 0b0101));        // e01 e01 e23 e23
    const __m256d shifted = _mm256_permute4x64_pd(d, _MM_SHUFFLE(2, 1, 0, 0));   // d0 d0 d1 d2
    const __m256d first_pair = _mm256_permute4x64_pd(pairs, 0);                  // e01 in every lane
    const __m256d base = _mm256_blend_pd(_mm256_blend_pd(zero, shifted, 0b0010), first_pair, 0b1100);
    const __m256d partial = _mm256_add_pd(base, _mm256_blend_pd(zero, shifted, 0b1000));
    const __m256d windows = _mm256_add_pd(w, partial);
    sums = _mm256_add_pd(sums, _mm256_mul_pd(windows, windows));
    squares = _mm256_add_pd(squares, _mm256_mul_pd(in, in));
    const __m256d change = _mm256_add_pd(pairs, _mm256_permute4x64_pd(pairs, _MM_SHUFFLE(1, 0, 3, 2)));
    w = _mm256_add_pd(w, change);
  }
  _mm256_storeu_pd(s, sums);
  _mm256_storeu_pd(q, squares);
  const double after = _mm256_cvtsd_f64(w);
  _mm256_zeroupper();  // the caller's scalar code is SSE
  return after;
}
#endif

bool Supports(RatioStepsKernel kernel) {
#ifdef ALLANLAB_HAVE_AVX2_RATIO
  if (kernel == RatioStepsKernel::kAvx2) return CpuHasAvx2();
#endif
  return kernel != RatioStepsKernel::kAvx2;
}

}  // namespace

bool RatioStepsKernelRuns(RatioStepsKernel kernel) { return Supports(kernel); }

double RatioWindowSteps(const double* x0, const double* x1, const double* x2, const double* x3, std::int64_t groups,
                        double window, double* s, double* q, RatioStepsKernel kernel) {
#ifdef ALLANLAB_HAVE_AVX2_RATIO
  if (kernel != RatioStepsKernel::kPortable && Supports(RatioStepsKernel::kAvx2)) {
    return Avx2Steps(x0, x1, x2, x3, groups, window, s, q);
  }
#endif
  (void)kernel;
  return PortableSteps(x0, x1, x2, x3, groups, window, s, q);
}

}  // namespace allanlab::estimators
