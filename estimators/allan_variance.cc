#include "estimators/allan_variance.h"

#include <memory>
#include <stdexcept>
#include <string>

#include "estimators/difference_sums.h"
#include "estimators/phase_integral.h"

namespace allanlab::estimators {

// The same sums as the statistic values of allan_family.h (cache-blocked passes over the phase
// about ReferenceLevel, shared by all m), without the tau grid and the summary.
std::vector<double> AllanVariance(std::span<const double> rate, std::span<const std::int64_t> ms,
                                  AvarEstimatorKind kind) {
  const auto n = static_cast<std::int64_t>(rate.size());
  const sim::RecordShape shape{n, kind};
  for (std::int64_t m : ms) {
    std::string why;
    if (!sim::IsValidAveragingFactor(m, shape, &why)) throw std::invalid_argument(why);
  }
  // Not zero-filled: every element is written before it is read.
  const auto storage = std::make_unique_for_overwrite<double[]>(rate.size() + 1);
  const std::span<double> phase(storage.get(), rate.size() + 1);
  std::vector<double> sums(ms.size());
  const double reference = ReferenceLevel(rate);
  if (kind == AvarEstimatorKind::kOverlapping) {
    IntegrateAndSumOverlappingDifferences(rate, reference, 2, ms, phase, sums);
  } else {
    IntegrateAbout(rate, reference, phase);
    StridedDifferenceSums(phase, 2, ms, sums);
  }
  std::vector<double> result(ms.size());
  for (std::size_t k = 0; k < ms.size(); ++k) {
    const sim::AllanStarts starts = sim::AllanDifferenceStarts(ms[k], shape);
    const auto m = static_cast<double>(ms[k]);
    result[k] = sums[k] / (2.0 * static_cast<double>(starts.count) * m * m);
  }
  return result;
}

std::vector<std::int64_t> OctaveAveragingFactors(std::int64_t max_m) {
  std::vector<std::int64_t> ms;
  for (std::int64_t m = 1; m <= max_m; m *= 2) ms.push_back(m);
  return ms;
}

}  // namespace allanlab::estimators
