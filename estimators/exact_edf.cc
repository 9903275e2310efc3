#include "estimators/exact_edf.h"

#include <algorithm>
#include <string>

namespace allanlab::estimators {

std::vector<AvarMoments> ModelAvarMoments(const sim::SensorModel& model,
                                          std::span<const std::int64_t> ms,
                                          const sim::RecordShape& shape) {
  std::int64_t max_m = 0;
  for (std::int64_t m : ms) {
    if (sim::IsValidAveragingFactor(m, shape, nullptr)) max_m = std::max(max_m, m);
  }
  std::vector<AvarMoments> moments(ms.size());
  if (max_m == 0) return moments;
  // One autocovariance serves every m: its length is what the longest lag of the largest m needs.
  const std::vector<double> r = model.GaussianAutocovariance(shape.num_samples + 2 * max_m);
  for (std::size_t i = 0; i < ms.size(); ++i) {
    if (sim::IsValidAveragingFactor(ms[i], shape, nullptr)) {
      moments[i] = ExactAvarMoments(r, ms[i], shape);
    }
  }
  return moments;
}

std::vector<double> ModelAvarEdf(const sim::SensorModel& model, std::span<const std::int64_t> ms,
                                 const sim::RecordShape& shape) {
  std::vector<double> edf;
  edf.reserve(ms.size());
  for (const AvarMoments& moments : ModelAvarMoments(model, ms, shape))
    edf.push_back(moments.edf());
  return edf;
}

}  // namespace allanlab::estimators
