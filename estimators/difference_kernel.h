#pragma once
// The inner loop of every Allan-family statistic: sums of squared lag-m finite differences of a
// phase record x (NIST SP 1065 §5.2: the Allan, Hadamard and modified statistics are all means of
// such squares). Order 1: D_t = x_{t+m} - x_t; order 2: D_t = x_{t+2m} - 2 x_{t+m} + x_t;
// order 3: D_t = x_{t+3m} - 3 x_{t+2m} + 3 x_{t+m} - x_t.
//
// Results are accumulated in kLanes partial sums, lane = t mod kLanes, each in increasing t.
// So a sum over [lo, hi) is bit-identical however the range is split into calls, which lets the
// cache-blocked passes give every tau the same value whatever other taus share the pass.
// The AVX2+FMA version is chosen once at run time when the CPU has it; the portable one differs
// from it only by rounding (it has no fused multiply-add).
#include <array>
#include <cmath>
#include <cstdint>

namespace allanlab::estimators {

inline constexpr int kLanes = 16;
using Lanes = std::array<double, kLanes>;

// lanes[t mod kLanes] += D_t^2 for t in [lo, hi), order 1, 2 or 3. Reads x[lo .. hi - 1 + order*m].
void AccumulateSquaredDifferences(const double* x, int order, std::int64_t m, std::int64_t lo,
                                  std::int64_t hi, Lanes* lanes);

// The same for lags m and 2m at once (order 2): the two share the loads of x_t and x_{t+2m},
// which the octave grid makes worth having. Reads x[lo .. hi - 1 + 4m].
void AccumulateSquaredSecondDifferencesPair(const double* x, std::int64_t m, std::int64_t lo,
                                            std::int64_t hi, Lanes* lanes_m, Lanes* lanes_2m);

// sum_{t=lo}^{hi-1} D_t^2, lanes flushed into a compensated total every few thousand terms.
double SumSquaredDifferences(const double* x, int order, std::int64_t m, std::int64_t lo,
                             std::int64_t hi);

// Sum of the lanes in a fixed order.
double SumLanes(const Lanes& lanes);

// Name of the implementation in use ("avx2+fma" or "portable"), for benchmark records.
const char* DifferenceKernelName();

// Kahan–Babuška (Neumaier) running sum: the blocked passes add one partial sum per block and
// tau, so a 1e8-term sum loses no more than a few units in the last place.
struct CompensatedSum {
  double sum = 0.0;
  double compensation = 0.0;
  void Add(double v) {
    const double t = sum + v;
    compensation += std::abs(sum) >= std::abs(v) ? (sum - t) + v : (v - t) + sum;
    sum = t;
  }
  double Value() const { return sum + compensation; }
};

}  // namespace allanlab::estimators
