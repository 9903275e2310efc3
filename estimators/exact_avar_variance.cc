#include "estimators/exact_avar_variance.h"

#include <algorithm>
#include <cstdlib>
#include <vector>

namespace allanlab::estimators {

std::vector<long double> PhaseVariogram(std::span<const double> autocovariance, std::int64_t lags) {
  std::vector<long double> variogram(static_cast<std::size_t>(std::max<std::int64_t>(lags, 1)), 0.0L);
  long double increment = autocovariance[0];  // V(k+1) - V(k) = R(0) + 2 sum_{j=1}^{k} R(j)
  for (std::int64_t k = 0; k + 1 < lags; ++k) {
    if (k > 0) increment += 2.0L * autocovariance[k];
    variogram[k + 1] = variogram[k] + increment;
  }
  return variogram;
}

AvarMoments ExactAvarMoments(std::span<const double> autocovariance, std::int64_t m,
                             const sim::RecordShape& shape) {
  const sim::AllanStarts starts = sim::AllanDifferenceStarts(m, shape);
  if (starts.count == 0) return {};
  const std::int64_t max_lag = (starts.count - 1) * starts.stride + 2 * m;
  return ExactAvarMomentsFromVariogram(PhaseVariogram(autocovariance, max_lag + 1), m, shape);
}

AvarMoments ExactAvarMomentsFromVariogram(std::span<const long double> variogram, std::int64_t m,
                                          const sim::RecordShape& shape) {
  const sim::AllanStarts starts = sim::AllanDifferenceStarts(m, shape);
  if (starts.count == 0) return {};
  auto v = [&](std::int64_t k) { return variogram[static_cast<std::size_t>(std::llabs(k))]; };
  const long double scale = -1.0L / (2.0L * m * m);
  auto cov_d = [&](std::int64_t k) {  // Cov(D_s, D_{s+k}), D the Allan difference
    return scale * (6.0L * v(k) - 4.0L * v(k + m) - 4.0L * v(k - m) + v(k + 2 * m) + v(k - 2 * m));
  };
  const long double c0 = cov_d(0);
  long double sum = starts.count * c0 * c0;
  for (std::int64_t i = 1; i < starts.count; ++i) {
    const long double c = cov_d(i * starts.stride);
    sum += 2.0L * (starts.count - i) * c * c;
  }
  AvarMoments moments;
  moments.mean = static_cast<double>(0.5L * c0);
  moments.variance = static_cast<double>(sum / (2.0L * starts.count * starts.count));
  return moments;
}

}  // namespace allanlab::estimators
