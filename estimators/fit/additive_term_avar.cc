#include "estimators/fit/additive_term_avar.h"

#include "estimators/fit/parametric_fit.h"

namespace allanlab::estimators {

const std::vector<double>* AdditiveTermAvar::Part(std::size_t slot, const ParametricTerm& term,
                                                  std::span<const double> params,
                                                  const sim::SensorModel& base,
                                                  std::span<const double> band_key) {
  if (!base.terms.empty()) return nullptr;
  if (cache_.size() <= slot) cache_.resize(slot + 1);
  std::vector<double> key(params.begin(), params.end());
  key.insert(key.end(), band_key.begin(), band_key.end());
  auto& cache = cache_[slot];
  auto it = cache.find(key);
  if (it != cache.end()) return &it->second;
  sim::SensorModel m = base;
  term.ApplyTo(params, &m);
  const bool terms_only = m.band_limit.kind == base.band_limit.kind &&
                          m.band_limit.cutoff_hz == base.band_limit.cutoff_hz &&
                          m.angle_quantizer.has_value() == base.angle_quantizer.has_value() &&
                          m.rate_quantizer.has_value() == base.rate_quantizer.has_value() &&
                          !base.angle_quantizer && !base.rate_quantizer;
  if (!terms_only) return nullptr;
  std::vector<double> part(curve_.size(), 0.0);
  if (!m.terms.empty()) part = ModelAvarOnCurve(m, curve_);
  // Bounded: the fits visit tens of points; a wandering one must not grow without limit.
  if (cache.size() >= 64) cache.clear();
  return &cache.emplace(std::move(key), std::move(part)).first->second;
}

}  // namespace allanlab::estimators
