#pragma once
// Exact covariance structure of the Allan-variance estimator for Gaussian noise with a known
// (generalised) autocovariance (docs/theory.md §3.1). The Allan difference is a lag-m second
// difference of the integrated record (the phase), so every covariance follows from the phase
// variogram V(k) = E[(Y_{t+k} - Y_t)^2] = k R(0) + 2 sum_{j=1}^{k-1} (k - j) R(j): O(N) per m.
#include <cstdint>
#include <span>
#include <vector>

#include "sim/avar_theory.h"

namespace allanlab::estimators {

struct AvarMoments {
  double mean = 0.0;      // E[AVAR_hat(m)]
  double variance = 0.0;  // Var(AVAR_hat(m)), Isserlis (Gaussian noise)
  double edf() const { return variance > 0.0 ? 2.0 * mean * mean / variance : 0.0; }
};

// `autocovariance[j]`, j = 0..N+2m-1 (generalised: additive constants cancel).
// Precondition: 1 <= m <= N/2.
AvarMoments ExactAvarMoments(std::span<const double> autocovariance, std::int64_t m,
                             const sim::RecordShape& shape);

// The phase variogram V(0..lags-1) from `autocovariance` (at least lags - 1 values), in long
// double (for random walk V grows like k^3 and the fourth differences of it cancel).
std::vector<long double> PhaseVariogram(std::span<const double> autocovariance, std::int64_t lags);

// ExactAvarMoments from a variogram shared by several m (the same bits: V does not depend on m, so
// one of the longest length serves every m instead of an O(N) rebuild per m).
// Precondition: 1 <= m <= N/2 and variogram.size() > (count - 1) stride + 2m (N + 1 suffices).
AvarMoments ExactAvarMomentsFromVariogram(std::span<const long double> variogram, std::int64_t m,
                                          const sim::RecordShape& shape);

// The variogram as pairs of doubles, hi + lo == V exactly (hi is V rounded to double; V's 64-bit
// significand leaves lo at most 11 bits). The O(N) loops per m form the second difference
// V(j + m) - 2V(j) + V(|j - m|) from the pairs in double-double arithmetic (error-free sums of the
// his, the los added, one rounding to double), which vectorises, where three 80-bit additions per
// lag bound the loop; the long doubles round three times at 64 bits before that last rounding, so
// the two could differ in the last bit of a difference that V's size cancels (in
// tests/estimators/split_variogram_test.cc's models they agree to the bit). Empty when
// some V does not split exactly (not finite, or outside double's range), or beyond 2^24 lags
// (memory): the long doubles are read then.
struct SplitVariogram {
  std::vector<double> hi, lo;
};
SplitVariogram SplitPhaseVariogram(std::span<const long double> variogram);

// Working memory of the O(N) moment sums, reused across the m of one grid. A loop over m that
// passes one per thread touches its pages once: allocating the record-sized buffers afresh for
// each m (zeroed, and faulted in page by page) was over half of the exact theory's time at 1e7
// samples. Without one, each call allocates its own.
struct MomentScratch {
  std::vector<double> first, second;
};

// The same moments, reading V from `split` (SplitPhaseVariogram(variogram), or empty) where it
// can (see SplitVariogram); the same bits with or without `scratch`.
AvarMoments ExactAvarMomentsFromVariogram(std::span<const long double> variogram, const SplitVariogram& split,
                                          std::int64_t m, const sim::RecordShape& shape,
                                          MomentScratch* scratch = nullptr);

// Moments of the overlapping Hadamard estimate OHVAR_hat(m) = (1/T) sum_{t<T} H_t^2 on N rate
// samples, T = N - 3m + 1, H_t the third difference of the phase at step m over m sqrt(6) (the
// filter of exact_quadratic_moments.h), from the same variogram: Cov(H_s, H_{s+k}) is the third
// power of the symmetric second difference at step m applied to V, over 12 m^2, so the cost is
// O(N) per m where the filter form costs O(3m) per lag (docs/theory.md §3.1).
// Zero moments unless 1 <= m and 3m <= N. Precondition: variogram.size() > N. The same bits with
// or without `scratch`.
AvarMoments ExactOhvarMomentsFromVariogram(std::span<const long double> variogram, std::int64_t m,
                                           std::int64_t num_samples, MomentScratch* scratch = nullptr);
// The same from `split` (SplitPhaseVariogram(variogram), or empty) where it can.
AvarMoments ExactOhvarMomentsFromVariogram(std::span<const long double> variogram, const SplitVariogram& split,
                                           std::int64_t m, std::int64_t num_samples, MomentScratch* scratch = nullptr);

}  // namespace allanlab::estimators
