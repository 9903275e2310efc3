#pragma once
// The inner loop of every Allan-family statistic: sums of squared lag-m finite differences of a
// phase record x (NIST SP 1065 §5.2: the Allan, Hadamard and modified statistics are all means of
// such squares). Order 1: D_t = x_{t+m} - x_t; order 2: D_t = x_{t+2m} - 2 x_{t+m} + x_t;
// order 3: D_t = x_{t+3m} - 3 x_{t+2m} + 3 x_{t+m} - x_t.
//
// Results are accumulated in kLanes partial sums, lane = t mod kLanes, each in increasing t.
// So a sum over [lo, hi) is bit-identical however the range is split into calls, which lets the
// cache-blocked passes give every tau the same value whatever other taus share the pass.
// The AVX-512 and AVX2+FMA versions are chosen once at run time when the CPU has them and give
// the same bits; the portable one differs from them only by rounding (it has no fused
// multiply-add).
#include <array>
#include <cmath>
#include <cstdint>
#include <string_view>

namespace allanlab::estimators {

inline constexpr int kLanes = 16;
using Lanes = std::array<double, kLanes>;

// lanes[t mod kLanes] += D_t^2 for t in [lo, hi), order 1, 2 or 3. Reads x[lo .. hi - 1 + order*m].
void AccumulateSquaredDifferences(const double* x, int order, std::int64_t m, std::int64_t lo,
                                  std::int64_t hi, Lanes* lanes);

// The same (order 2) for the doubling chain of lags m, 2m, 4m, ..., 2^(count-1) m, 1 <= count <=
// kMaxChain: lag 2^j m reuses the loads of x_t and x_{t+2^j m} made for the lag before it, so an
// octave grid costs about one load per lag and term instead of three. lanes[j] belongs to lag
// 2^j m. Reads x[lo .. hi - 1 + 2^count m]. Same bits as AccumulateSquaredDifferences per lag.
inline constexpr int kMaxChain = 8;
void AccumulateSquaredSecondDifferencesChain(const double* x, std::int64_t m, int count,
                                             std::int64_t lo, std::int64_t hi, Lanes* const* lanes);

// sum_{t=lo}^{hi-1} D_t^2, lanes flushed into a compensated total every few thousand terms.
double SumSquaredDifferences(const double* x, int order, std::int64_t m, std::int64_t lo,
                             std::int64_t hi);

// Sum of the lanes in a fixed order.
double SumLanes(const Lanes& lanes);

// Name of the implementation in use ("avx512", "avx2+fma" or "portable"), for benchmark records.
const char* DifferenceKernelName();

// Switches to the named implementation if this CPU runs it (false otherwise), so that a test can
// compare them. Not safe while another thread uses the kernels.
bool UseDifferenceKernelForTesting(std::string_view name);

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
