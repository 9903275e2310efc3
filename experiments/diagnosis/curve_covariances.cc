#include "experiments/diagnosis/curve_covariances.h"

namespace allanlab::experiments::detail {

std::shared_ptr<const estimators::AvarCovarianceModel> CurveCovariances::For(
    const estimators::AvarCurve& curve, const std::vector<estimators::Coefficient>& terms) {
  // The model's preconditions; a fit of another curve builds its own (or fails) as before.
  if (!curve.IsValid(nullptr) || curve.estimator != sim::AvarEstimatorKind::kOverlapping || curve.num_samples <= 0) {
    return nullptr;
  }
  const double period_s = curve.sample_clock.period_s();
  std::lock_guard<std::mutex> lock(mutex_);
  for (const Entry& e : entries_) {
    if (e.num_samples == curve.num_samples && e.period_s == period_s && e.m == curve.m && e.terms == terms) {
      return e.model;
    }
  }
  entries_.push_back({curve.num_samples, period_s, curve.m, terms,
                      std::make_shared<const estimators::AvarCovarianceModel>(curve, terms)});
  return entries_.back().model;
}

}  // namespace allanlab::experiments::detail
