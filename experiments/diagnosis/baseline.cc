#include "experiments/diagnosis/baseline.h"

#include <cmath>

#include "estimators/avar.h"
#include "experiments/diagnosis/gap.h"

namespace allanlab::experiments {
namespace detail {
namespace {

using estimators::Coefficient;


// The curve against a linear fit's expected OAVAR with the curve's own (Greenhall-Riley) EDFs:
// a yardstick that does not depend on the model the way each fit's own chi2 does.
double CurveChi2(const estimators::FitSummary& fit, const estimators::AvarCurve& curve) {
  const auto mean = LinearModel(fit, 1.0 / curve.sample_period_s).ExpectedAvar(curve.m, {curve.num_samples, curve.estimator});
  double chi2 = 0.0;
  for (std::size_t i = 0; i < curve.size(); ++i) {
    const double z = ZFromChiSquare(curve.avar[i], mean[i], curve.edf[i]);
    chi2 += std::isfinite(z) ? z * z : 1e300;
  }
  return chi2;
}

}  // namespace


sim::SensorModel LinearModel(const estimators::FitSummary& fit, double sample_rate_hz) {
  sim::SensorModel model;
  model.name = "fitted";
  model.sample_rate_hz = sample_rate_hz;
  for (Coefficient c : estimators::kAllCoefficients) {
    const auto& e = fit.at(c);
    if (e.fitted && e.value_si > 0.0) model.terms.push_back(estimators::TermFor(c, e.value_si));
  }
  return model;
}


// GLS, falling back to WLS when the model covariance of the curve is singular, or when the GLS
// iteration has collapsed onto a degenerate model (a strong warm-up drift, benchmark #42: R alone,
// N dropped, the short taus 1e6 sd below the model): WLS fits the curve > 100 x better there on
// a common yardstick (CurveChi2), a margin GLS never loses by on a curve it describes. The
// fallback is named in *note.
bool FitLinear(const DiagnoseOptions& options, const estimators::AvarCurve& curve,
               estimators::FitSummary* fit, std::string* note) {
  estimators::FitOptions fo;
  fo.method = estimators::FitMethod::kGls;
  fo.terms = options.terms;
  estimators::FitSummary wls;
  estimators::FitOptions wo = fo;
  wo.method = estimators::FitMethod::kWls;
  if (estimators::FitAvarModel(fo, curve, fit)) {
    const double gls_chi2 = CurveChi2(*fit, curve);
    if (!estimators::FitAvarModel(wo, curve, &wls) || !(CurveChi2(wls, curve) * 100.0 < gls_chi2)) return true;
    *fit = std::move(wls);
    if (note != nullptr) *note = "GLS settled on a degenerate model (chi2 on the curve's own EDFs 100 x WLS's); WLS used";
    return true;
  }
  const std::string gls_message = fit->message;
  if (!estimators::FitAvarModel(wo, curve, fit)) return false;
  if (note != nullptr) *note = "GLS fit failed (" + gls_message + "); WLS used";
  return true;
}

}  // namespace detail


bool RecordCurve(std::span<const double> rate, double tau0, estimators::AvarCurve* curve,
                 std::string* why) {
  estimators::AvarOptions o;
  o.statistic = estimators::Statistic::kAllanOverlapping;
  o.sample_period_s = tau0;
  o.taus.kind = estimators::TauGridKind::kLogDense;
  o.taus.points_per_decade = 10;
  estimators::AvarSummary s;
  if (!estimators::ComputeAvar(o, rate, &s)) {
    *why = s.message;
    return false;
  }
  estimators::AvarCurve c;
  c.sample_period_s = tau0;
  c.num_samples = s.num_samples;
  c.estimator = sim::AvarEstimatorKind::kOverlapping;
  for (const auto& p : s.points) {
    if (!(p.value > 0.0)) continue;  // a constant stretch: no variance to fit
    c.m.push_back(p.m);
    c.tau_s.push_back(p.tau_s);
    c.avar.push_back(p.value);
    c.edf.push_back(p.edf > 0.0 ? p.edf : 1.0);
  }
  if (c.size() < detail::kMinTaus) {
    *why = "the record gives " + std::to_string(c.size()) + " usable taus (need " +
           std::to_string(detail::kMinTaus) + "): too short or constant";
    return false;
  }
  *curve = std::move(c);
  return true;
}

}  // namespace allanlab::experiments
