#pragma once
// Exact expected Allan variance of discrete-time processes (docs/theory.md §1.2, §2).
// Shared by every noise term so that one quadratic-form recipe covers them all.
#include <algorithm>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>

namespace allanlab::sim {

// Which Allan estimator's expectation is asked for. For stationary-increment noise both have the
// same expectation; they differ for processes started from a zero state (Kasdin flicker) and for
// deterministic signals.
enum class AvarEstimatorKind { kOverlapping, kNonOverlapping };

// The record an expectation refers to: N samples and the estimator applied to them.
struct RecordShape {
  std::int64_t num_samples = 0;
  AvarEstimatorKind estimator = AvarEstimatorKind::kOverlapping;
};

// Start indices t of the Allan differences (ybar_{t+m} - ybar_t) the estimator averages over:
// all t in [0, N-2m] (overlapping) or t = 0, m, 2m, ... with t + 2m <= N (non-overlapping).
struct AllanStarts {
  std::int64_t count = 0;   // number of differences averaged
  std::int64_t stride = 1;  // spacing of the start indices
};
AllanStarts AllanDifferenceStarts(std::int64_t m, const RecordShape& shape);

// Weight a(j) of lag j in the Allan quadratic form: 2m-3j for 0<=j<=m, -(2m-j) for m<j<2m.
double AllanLagWeight(std::int64_t m, std::int64_t j);

// AVAR(m) = (1/(2 m^2)) sum_{|j|<2m} a(|j|) R(j)   (docs/theory.md §1.2).
// `autocovariance[j]` is the (generalised) autocovariance at lag j >= 0, in rate^2; it needs at
// least 2m entries. Additive constants in R cancel, so generalised autocovariances of random
// walk and flicker work as they are.
double AvarFromAutocovariance(std::int64_t m, std::span<const double> autocovariance);

// Exact E[AVAR_hat(m)] of y_k = sum_v p_{k+offset-v} w_v, w iid with variance `innovation_var`,
// for a causal impulse response p started from a zero state `offset` samples before y_0
// (docs/theory.md §2.5.3). `cumulative_p[v] = sum_{k<=v} p_k` must cover indices
// up to offset + N - 1.
double FiniteRecordAvar(std::span<const double> cumulative_p, double innovation_var,
                        std::int64_t m, std::int64_t offset, const RecordShape& shape);
// FiniteRecordAvar before its scale: the sum over the Allan differences, which does not depend on
// the innovation variance, so one sum serves every variance (the same bits as FiniteRecordAvar).
struct FiniteRecordSum {
  long double total = 0.0L;
  std::int64_t count = 0;  // Allan differences averaged (0: m too large for the record)
};
FiniteRecordSum FiniteRecordAvarSum(std::span<const double> cumulative_p, std::int64_t m, std::int64_t offset,
                                    const RecordShape& shape);
double ScaledFiniteRecordAvar(const FiniteRecordSum& sum, double innovation_var);

// Checks 1 <= m and 2m <= N; writes the reason otherwise.
bool IsValidAveragingFactor(std::int64_t m, const RecordShape& shape, std::string* why);

}  // namespace allanlab::sim

namespace allanlab::sim {

// Exact estimator value (1/(2 T)) sum_t D_t^2 for a deterministic signal y whose Allan differences
// D_t vanish outside starts t in [t_lo, t_hi] (a step, a transient). `y(k)` is sample k, O(m + span).
// A template: y is read once per sample of a span that reaches the record's length at the longest
// taus, and an indirect call per sample was most of the cost of a step's expected AVAR in a fit.
template <class Signal>
double DeterministicAvar(const Signal& y, std::int64_t t_lo, std::int64_t t_hi, std::int64_t m,
                         const RecordShape& shape) {
  const AllanStarts starts = AllanDifferenceStarts(m, shape);
  if (starts.count == 0) return 0.0;
  const std::int64_t last = (starts.count - 1) * starts.stride;
  // First and last admissible start inside [t_lo, t_hi] on the estimator's stride.
  std::int64_t first = std::max<std::int64_t>(t_lo, 0);
  first = (first + starts.stride - 1) / starts.stride * starts.stride;
  const std::int64_t stop = std::min(t_hi, last);
  if (first > stop) return 0.0;
  // Prefix sums of y over [first, stop + 2m), each written once (no zeroing: the span is up to
  // 16 bytes x 4m).
  const auto prefix = std::make_unique_for_overwrite<long double[]>(static_cast<std::size_t>(stop - first + 2 * m + 1));
  prefix[0] = 0.0L;
  for (std::int64_t k = first; k < stop + 2 * m; ++k) prefix[k - first + 1] = prefix[k - first] + y(k);
  long double sum = 0.0L;
  for (std::int64_t t = first; t <= stop; t += starts.stride) {
    const std::int64_t i = t - first;
    const long double d = (prefix[i + 2 * m] - 2.0L * prefix[i + m] + prefix[i]) / m;
    sum += d * d;
  }
  return static_cast<double>(sum / (2.0L * starts.count));
}

}  // namespace allanlab::sim
