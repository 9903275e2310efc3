#include "estimators/fit/fit_model.h"

#include <cmath>
#include <cstdio>
#include <sstream>

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

namespace {

// The route of the header's list: one fit, no poor-fit handling.
bool FitRoute(const ModelFitOptions& options, const AvarCurve& curve, ModelFitSummary* summary) {
  if (!options.extra.empty()) {
    ParametricFitOptions p;
    p.method = options.method;
    p.terms = options.terms;
    p.extra = options.extra;
    p.uncertainty = options.uncertainty;
    p.bootstrap = options.bootstrap;
    p.covariance = options.covariance;
    p.select_terms = options.select_terms;  // the linear terms; the parametric ones are kept
    ParametricFitSummary s;
    if (!FitAvarModelWithTerms(p, curve, &s)) {
      summary->fit = s.base;
      return false;
    }
    summary->fit = s.base;
    summary->fit.tau_min_s = curve.tau_s.front();
    summary->fit.tau_max_s = curve.tau_s.back();
    bool band_limit_fitted = false;
    for (std::size_t i = 0; i < options.extra.size() && i < s.extra.size(); ++i) {
      band_limit_fitted = band_limit_fitted || (options.extra[i]->modifies_other_terms() && s.extra[i].fitted);
    }
    summary->fit.band_limit = band_limit_fitted ? "fitted as listed in the terms" : "none among the fitted terms";
    summary->extra_terms = options.extra;
    summary->extra = s.extra;
    summary->ok = true;
    return true;
  }
  BandLimitedFitOptions b;
  b.fit.method = options.method;
  b.fit.terms = options.terms;
  b.fit.select_terms = options.select_terms;
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

int FittedParameters(const FitSummary& fit) { return fit.taus_used - fit.dof; }

void TryExtended(const ModelFitOptions& options, const AvarCurve& curve, ModelFitSummary* summary) {
  std::vector<std::pair<std::string, std::vector<std::shared_ptr<const ParametricTerm>>>> candidates;
  const std::vector<std::shared_ptr<const ParametricTerm>> kept = summary->extra_terms;  // the band-limit found
  std::string kept_name;
  for (const auto& t : kept) kept_name.append("+").append(t->short_name());
  for (const char* id : {"GM", "H"}) {
    std::vector<std::shared_ptr<const ParametricTerm>> terms = {MakeParametricTerm(id)};
    terms.insert(terms.end(), kept.begin(), kept.end());
    candidates.emplace_back(std::string(id).append(kept_name), terms);
  }
  if (kept.empty()) {
    for (sim::LowPassKind kind : {sim::LowPassKind::kFirstOrder, sim::LowPassKind::kButterworth2}) {
      candidates.emplace_back(kind == sim::LowPassKind::kFirstOrder ? "BW" : "BW2",
                              std::vector<std::shared_ptr<const ParametricTerm>>{
                                  MakeBandLimitTerm(kind, options.bw_sampling, options.bw_oversampling)});
    }
  }
  // An extended model is reported only when it lowers the AIC of the fit it extends: a nested
  // model whose chi2 came out higher is a local minimum, not evidence for the extra term.
  const double base_aic = summary->fit.chi2 + 2.0 * FittedParameters(summary->fit);
  for (auto& [name, terms] : candidates) {
    ModelFitOptions o = options;
    o.extra = terms;
    o.uncertainty = FitUncertainty::kCovariance;
    ModelFitSummary s;
    if (!FitRoute(o, curve, &s)) continue;
    bool all = true;
    for (const ParametricEstimate& e : s.extra) all = all && e.fitted;
    if (!all) continue;
    ExtendedFit x;
    x.name = name;
    x.fit = s.fit;
    x.extra_terms = terms;
    x.extra = s.extra;
    x.aic = s.fit.chi2 + 2.0 * FittedParameters(s.fit);
    x.fits = s.fit.dof > 0 && !IsPoorFit(s.fit);
    summary->extended.push_back(x);
    if (x.aic >= base_aic) continue;
    if (summary->best_extended < 0 || x.aic < summary->extended[summary->best_extended].aic) {
      summary->best_extended = static_cast<int>(summary->extended.size()) - 1;
    }
  }
}

void CrossCheck(const ModelFitOptions& options, const AvarCurve& curve, ModelFitSummary* summary) {
  ModelFitOptions o = options;
  o.method = FitMethod::kLogWls;
  o.uncertainty = FitUncertainty::kCovariance;
  o.extra = summary->extra_terms;  // the same model, band-limit included
  ModelFitSummary s;
  if (!FitRoute(o, curve, &s)) return;
  std::ostringstream os;
  for (Coefficient c : kAllCoefficients) {
    const CoefficientEstimate& g = summary->fit.at(c);
    const CoefficientEstimate& l = s.fit.at(c);
    if (!g.fitted || !l.fitted || !(g.sigma_si > 0.0)) continue;
    const double z = std::abs(g.value_si - l.value_si) / g.sigma_si;
    if (z <= 3.0) continue;
    char line[160];
    std::snprintf(line, sizeof line, "%s%s: GLS %.4g, log-WLS %.4g %s (%.1f sigma)",
                  os.tellp() > 0 ? "; " : "", std::string(CoefficientId(c)).c_str(),
                  ToDatasheetUnit(c, g.value_si), ToDatasheetUnit(c, l.value_si),
                  std::string(DatasheetUnit(c)).c_str(), z);
    os << line;
  }
  summary->method_disagreement = os.str();
}

}  // namespace

bool FitModel(const ModelFitOptions& options, const AvarCurve& curve, ModelFitSummary* summary) {
  *summary = ModelFitSummary{};
  std::string why;
  if (!options.IsValid(&why)) {
    summary->fit.message = why;
    return false;
  }
  if (!FitRoute(options, curve, summary)) return false;
  if (options.method == FitMethod::kSlope) return true;
  summary->poor_fit = IsPoorFit(summary->fit);
  if (summary->poor_fit) {
    summary->poor_chi2 = summary->fit.gof_chi2;
    summary->poor_dof = summary->fit.dof;
  }
  if (summary->poor_fit && options.try_extended_on_poor_fit && options.extra.empty()) {
    TryExtended(options, curve, summary);
    // A model that fits is the one to report: the IEEE coefficients of a wrong model are not
    // (MTi-G: B = 45 deg/h with the curve's floor at 6; with a Gauss-Markov term chi2 42 on 47).
    if (summary->best_extended >= 0 && summary->extended[summary->best_extended].fits) {
      const ExtendedFit& x = summary->extended[summary->best_extended];
      summary->fit = x.fit;
      summary->extra_terms = x.extra_terms;
      summary->extra = x.extra;
    }
  }
  if (options.cross_check_log_wls && options.method == FitMethod::kGls) CrossCheck(options, curve, summary);
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
