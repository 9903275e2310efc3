#include "estimators/fit/fit_model.h"

namespace allanlab::estimators {

bool ModelFitOptions::IsValid(std::string* why) const {
  if (terms.empty() && extra.empty()) {
    if (why) *why = "fit: no terms requested";
    return false;
  }
  if (!extra.empty() && method == FitMethod::kSlope) {
    if (why) *why = "fit: parametric terms need a fit method (gls, wls or logwls), not slope";
    return false;
  }
  if (bw_oversampling < 1 || bw_oversampling > 256) {
    if (why) *why = "fit: band-limit oversampling must be an integer in [1, 256]";
    return false;
  }
  if (uncertainty == FitUncertainty::kBootstrap && !bootstrap.IsValid(why)) return false;
  return true;
}

bool FitModel(const ModelFitOptions& options, const AvarCurve& curve, ModelFitSummary* summary) {
  *summary = ModelFitSummary{};
  std::string why;
  if (!options.IsValid(&why)) {
    summary->fit.message = why;
    return false;
  }
  if (!options.extra.empty()) {
    ParametricFitOptions p;
    p.method = options.method;
    p.terms = options.terms;
    p.extra = options.extra;
    p.uncertainty = options.uncertainty;
    p.bootstrap = options.bootstrap;
    p.covariance = options.covariance;
    ParametricFitSummary s;
    if (!FitAvarModelWithTerms(p, curve, &s)) {
      summary->fit = s.base;
      return false;
    }
    summary->fit = s.base;
    summary->fit.tau_min_s = curve.tau_s.front();
    summary->fit.tau_max_s = curve.tau_s.back();
    summary->fit.band_limit = "as listed in the terms";
    summary->extra_terms = options.extra;
    summary->extra = s.extra;
    summary->ok = true;
    return true;
  }
  BandLimitedFitOptions b;
  b.fit.method = options.method;
  b.fit.terms = options.terms;
  b.fit.select_terms = options.select_terms;
  b.fit.selection_level = options.selection_level;
  b.fit.uncertainty = options.uncertainty;
  b.fit.bootstrap = options.bootstrap;
  b.fit.covariance = options.covariance;
  b.policy = options.band_limit;
  b.sampling = options.bw_sampling;
  b.oversampling = options.bw_oversampling;
  b.detection_level = options.bw_detection_level;
  BandLimitedFitSummary s;
  if (!FitWithBandLimit(b, curve, &s)) {
    summary->fit = s.fit;
    return false;
  }
  summary->fit = s.fit;
  summary->band_limited = s.band_limited;
  if (s.band_limited) {
    summary->extra_terms = s.parametric.extra;
    summary->extra = s.extra;
  }
  summary->plain_chi2 = s.plain_chi2;
  summary->plain_dof = s.plain_dof;
  summary->ok = true;
  return true;
}

sim::SensorModel FittedModel(const AvarCurve& curve, const ModelFitSummary& summary) {
  ParametricFitOptions options;
  options.extra = summary.extra_terms;
  ParametricFitSummary fitted;
  fitted.base = summary.fit;
  fitted.extra = summary.extra;
  return FittedModel(options, curve, fitted);
}

}  // namespace allanlab::estimators
