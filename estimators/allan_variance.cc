#include "estimators/allan_variance.h"

#include <stdexcept>
#include <string>

namespace allanlab::estimators {

std::vector<double> AllanVariance(std::span<const double> rate, std::span<const std::int64_t> ms,
                                  AvarEstimatorKind kind) {
  const auto n = static_cast<std::int64_t>(rate.size());
  long double mean = 0.0L;
  for (double v : rate) mean += v;
  mean /= n > 0 ? n : 1;
  std::vector<double> prefix(rate.size() + 1, 0.0);
  long double acc = 0.0L;
  for (std::int64_t i = 0; i < n; ++i) prefix[i + 1] = static_cast<double>(acc += rate[i] - mean);

  std::vector<double> result;
  result.reserve(ms.size());
  const sim::RecordShape shape{n, kind};
  for (std::int64_t m : ms) {
    std::string why;
    if (!sim::IsValidAveragingFactor(m, shape, &why)) throw std::invalid_argument(why);
    const sim::AllanStarts starts = sim::AllanDifferenceStarts(m, shape);
    long double sum = 0.0L;
    for (std::int64_t i = 0; i < starts.count; ++i) {
      const std::int64_t t = i * starts.stride;
      const double d = prefix[t + 2 * m] - 2.0 * prefix[t + m] + prefix[t];
      sum += static_cast<long double>(d) * d;
    }
    result.push_back(static_cast<double>(sum / (2.0L * starts.count * m * m)));
  }
  return result;
}

std::vector<std::int64_t> OctaveAveragingFactors(std::int64_t max_m) {
  std::vector<std::int64_t> ms;
  for (std::int64_t m = 1; m <= max_m; m *= 2) ms.push_back(m);
  return ms;
}

}  // namespace allanlab::estimators
