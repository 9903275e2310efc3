#include "sim/avar_theory.h"

#include <algorithm>
#include <vector>

namespace allanlab::sim {

AllanStarts AllanDifferenceStarts(std::int64_t m, const RecordShape& shape) {
  const std::int64_t n = shape.num_samples;
  if (m < 1 || 2 * m > n) return {0, 1};
  if (shape.estimator == AvarEstimatorKind::kOverlapping) return {n - 2 * m + 1, 1};
  return {n / m - 1, m};
}

double AllanLagWeight(std::int64_t m, std::int64_t j) {
  if (j < 0) j = -j;
  if (j <= m) return static_cast<double>(2 * m - 3 * j);
  if (j < 2 * m) return -static_cast<double>(2 * m - j);
  return 0.0;
}

double AvarFromAutocovariance(std::int64_t m, std::span<const double> autocovariance) {
  // Long double: for random walk the lag terms grow like m^3 and cancel to O(m).
  long double sum = static_cast<long double>(2 * m) * autocovariance[0];
  for (std::int64_t j = 1; j < 2 * m; ++j) {
    sum += 2.0L * AllanLagWeight(m, j) * static_cast<long double>(autocovariance[j]);
  }
  return static_cast<double>(sum / (2.0L * m * m));
}

double FiniteRecordAvar(std::span<const double> cumulative_p, double innovation_var,
                        std::int64_t m, std::int64_t offset, const RecordShape& shape) {
  const AllanStarts starts = AllanDifferenceStarts(m, shape);
  if (starts.count == 0) return 0.0;
  const std::int64_t last_start = (starts.count - 1) * starts.stride;
  const std::int64_t e_max = offset + last_start + 2 * m - 1;
  auto s = [&](std::int64_t v) -> double { return v < 0 ? 0.0 : cumulative_p[v]; };
  // G(L) = sum_{e<=L} g_e^2 with g_e = (S(e) - 2 S(e-m) + S(e-2m)) / m, read at the estimator's
  // end points L = offset + t + 2m - 1 in one pass.
  long double g_cumulative = 0.0L, sum_at_ends = 0.0L;
  std::int64_t next_end = offset + 2 * m - 1;
  for (std::int64_t e = 0; e <= e_max; ++e) {
    const double g = (s(e) - 2.0 * s(e - m) + s(e - 2 * m)) / static_cast<double>(m);
    g_cumulative += static_cast<long double>(g) * g;
    if (e == next_end) {
      sum_at_ends += g_cumulative;
      next_end += starts.stride;
    }
  }
  return static_cast<double>(0.5L * innovation_var * sum_at_ends / starts.count);
}

bool IsValidAveragingFactor(std::int64_t m, const RecordShape& shape, std::string* why) {
  if (m < 1) {
    if (why) *why = "averaging factor m must be >= 1, got " + std::to_string(m);
    return false;
  }
  if (2 * m > shape.num_samples) {
    if (why) {
      *why = "averaging factor m = " + std::to_string(m) + " needs at least 2m samples, record has " +
             std::to_string(shape.num_samples);
    }
    return false;
  }
  return true;
}

}  // namespace allanlab::sim

namespace allanlab::sim {

double DeterministicAvar(const std::function<double(std::int64_t)>& y, std::int64_t t_lo,
                         std::int64_t t_hi, std::int64_t m, const RecordShape& shape) {
  const AllanStarts starts = AllanDifferenceStarts(m, shape);
  if (starts.count == 0) return 0.0;
  const std::int64_t last = (starts.count - 1) * starts.stride;
  // First and last admissible start inside [t_lo, t_hi] on the estimator's stride.
  std::int64_t first = std::max<std::int64_t>(t_lo, 0);
  first = (first + starts.stride - 1) / starts.stride * starts.stride;
  const std::int64_t stop = std::min(t_hi, last);
  if (first > stop) return 0.0;
  // Prefix sums of y over [first, stop + 2m).
  std::vector<long double> prefix(static_cast<std::size_t>(stop - first + 2 * m + 1), 0.0L);
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
