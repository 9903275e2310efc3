#include "estimators/exact_edf.h"

#include <algorithm>
#include <string>

#include "estimators/exact_quadratic_moments.h"

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
  // Every m's longest lag, (count - 1) stride + 2m, is at most N: one variogram serves them all.
  const std::vector<long double> variogram = PhaseVariogram(r, shape.num_samples + 1);
  const SplitVariogram split = SplitPhaseVariogram(variogram);
  // O(N) per m and the m independent: shared across threads when the caller runs none (inside
  // a parallel region this runs in the caller's thread alone). Each m's value lands in its own
  // slot, so the result is the same bits for any thread count.
  const auto count = static_cast<std::int64_t>(ms.size());
#pragma omp parallel if (count > 1)
  {
    MomentScratch scratch;  // one per thread, for all its m (exact_avar_variance.h)
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t i = 0; i < count; ++i) {
      if (sim::IsValidAveragingFactor(ms[i], shape, nullptr)) {
        moments[i] = ExactAvarMomentsFromVariogram(variogram, split, ms[i], shape, &scratch);
      }
    }
  }
  return moments;
}

std::vector<AvarMoments> ModelOhvarMoments(const sim::SensorModel& model, std::span<const std::int64_t> ms,
                                           std::int64_t num_samples) {
  std::vector<AvarMoments> moments(ms.size());
  auto computed = [&](std::int64_t m) { return TermCount(Statistic::kHadamardOverlapping, m, num_samples) >= 1; };
  if (std::none_of(ms.begin(), ms.end(), computed)) {
    return moments;
  }
  const std::vector<long double> variogram = PhaseVariogram(model.GaussianAutocovariance(num_samples + 1), num_samples + 1);
  const auto count = static_cast<std::int64_t>(ms.size());
#pragma omp parallel if (count > 1)
  {
    MomentScratch scratch;
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t i = 0; i < count; ++i) {
      if (computed(ms[i])) moments[i] = ExactOhvarMomentsFromVariogram(variogram, ms[i], num_samples, &scratch);
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

bool HasExactMoments(Statistic s) {
  return s == Statistic::kAllanNonOverlapping || s == Statistic::kAllanOverlapping ||
         s == Statistic::kModifiedAllan || s == Statistic::kHadamardNonOverlapping ||
         s == Statistic::kHadamardOverlapping;
}

std::vector<AvarMoments> ModelStatisticMoments(const sim::SensorModel& model, Statistic s,
                                               std::span<const std::int64_t> ms,
                                               std::int64_t num_samples) {
  if (s == Statistic::kAllanNonOverlapping || s == Statistic::kAllanOverlapping) {
    const sim::RecordShape shape{num_samples, s == Statistic::kAllanOverlapping
                                                  ? sim::AvarEstimatorKind::kOverlapping
                                                  : sim::AvarEstimatorKind::kNonOverlapping};
    return ModelAvarMoments(model, ms, shape);
  }
  std::vector<AvarMoments> moments(ms.size());
  if (!HasExactMoments(s)) return moments;
  if (s == Statistic::kHadamardOverlapping) return ModelOhvarMoments(model, ms, num_samples);
  const std::int64_t stride_per_m = s == Statistic::kHadamardNonOverlapping ? 1 : 0;
  std::int64_t max_lag = 0;
  for (std::int64_t m : ms) {
    const std::int64_t count = TermCount(s, m, num_samples);
    if (count < 1) continue;
    const std::int64_t stride = stride_per_m ? m : 1;
    max_lag = std::max(max_lag, (count - 1) * stride + 3 * m);
  }
  if (max_lag == 0) return moments;
  const std::vector<double> r = model.GaussianAutocovariance(max_lag + 1);
  for (std::size_t i = 0; i < ms.size(); ++i) {
    const std::int64_t count = TermCount(s, ms[i], num_samples);
    if (count < 1) continue;
    const std::vector<double> filter = DifferenceFilter(s, ms[i]);
    moments[i] = ExactQuadraticMoments(r, filter, count, stride_per_m ? ms[i] : 1);
  }
  return moments;
}

}  // namespace allanlab::estimators
