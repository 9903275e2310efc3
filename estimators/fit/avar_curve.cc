#include "estimators/fit/avar_curve.h"

#include <cmath>

namespace allanlab::estimators {

bool AvarCurve::IsValid(std::string* why) const {
  auto fail = [&](const std::string& msg) {
    if (why) *why = msg;
    return false;
  };
  if (!sample_clock.IsValid()) {
    return fail("curve: sample period must be > 0 s");
  }
  if (m.empty()) return fail("curve: no taus");
  if (tau_s.size() != m.size() || avar.size() != m.size() ||
      (!edf.empty() && edf.size() != m.size())) {
    return fail("curve: m, tau, avar and edf sizes differ");
  }
  for (std::size_t k = 0; k < m.size(); ++k) {
    if (m[k] < 1 || (k > 0 && m[k] <= m[k - 1])) return fail("curve: m must be ascending and >= 1");
    if (num_samples > 0 && 2 * m[k] > num_samples) return fail("curve: m above N/2");
    if (!(std::isfinite(avar[k]) && avar[k] > 0.0)) {
      return fail("curve: Allan variance at tau = " + std::to_string(tau_s[k]) +
                  " s is not a finite positive number");
    }
    if (!edf.empty() && !(std::isfinite(edf[k]) && edf[k] > 0.0)) {
      return fail("curve: EDF at tau = " + std::to_string(tau_s[k]) + " s is not positive");
    }
  }
  return true;
}

AvarCurve TauRange(const AvarCurve& curve, double min_tau_s, double max_tau_s) {
  AvarCurve out = curve;
  out.m.clear();
  out.tau_s.clear();
  out.avar.clear();
  out.edf.clear();
  for (std::size_t k = 0; k < curve.size(); ++k) {
    if (curve.tau_s[k] < min_tau_s || curve.tau_s[k] > max_tau_s) continue;
    out.m.push_back(curve.m[k]);
    out.tau_s.push_back(curve.tau_s[k]);
    out.avar.push_back(curve.avar[k]);
    if (!curve.edf.empty()) out.edf.push_back(curve.edf[k]);
  }
  return out;
}

AvarCurve CurveFromSummary(const AvarSummary& summary, std::int64_t min_m, std::int64_t max_m) {
  AvarCurve c;
  c.sample_clock = summary.options.sample_clock;
  c.num_samples = summary.num_samples;
  c.estimator = sim::AvarEstimatorKind::kOverlapping;
  for (const AvarPoint& p : summary.points) {
    if (p.m < min_m || p.m > max_m || !(p.value > 0.0)) continue;
    c.m.push_back(p.m);
    c.tau_s.push_back(p.tau_s);
    c.avar.push_back(p.value);
    c.edf.push_back(p.edf > 0.0 ? p.edf : 1.0);
  }
  return c;
}

}  // namespace allanlab::estimators
