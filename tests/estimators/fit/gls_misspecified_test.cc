// GLS on curves the IEEE 952 sum model cannot describe, fitted with Q, N, B, K, R only:
// white noise plus a strong Gauss-Markov bump, and white noise plus rate random walk behind a
// first-order band-limit. Noiseless expected curves (K - 1 cluster EDFs): the misfit is
// structural, not noise. Required:
//   - the misfit is flagged: p < 1e-6 and IsPoorFit;
//   - with a bump, the flicker term that imitates it stays below the bump: a flicker of
//     coefficient b has the plateau (2 ln2 / pi) b^2 = 0.441 b^2 over the curve's middle, the
//     Gauss-Markov AVAR peaks at 0.381 sigma^2 (parametric_term.h), so b > sigma would lie above
//     the bump everywhere; a fit that inflates B (as iterating Omega(theta) did on the ADIS
//     16405, fit_avar_model.h) breaks this.
// Not required: B below the slope reading min sigma / 0.6643. No weighted fit here meets it on
// these curves (log-WLS, WLS and GLS alike): the short taus, with by far the most degrees of
// freedom, pull the closest wrong model off the curve's minimum. With Omega iterated to a fixed
// point instead of held at the pilot, B came out about the same on the bump curves and lower on
// the band-limited one (1.5 vs 6.9 deg/h); what the iteration changed was chi2 (shrunk by
// 2 to 130 times here), which is why it is no longer done.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "estimators/fit/fit_avar_model.h"
#include "estimators/fit/parametric_fit.h"
#include "sim/units.h"
#include "tests/support/fit_curves.h"

namespace allanlab::estimators {
namespace {

using testing_support::LogDense;

AvarCurve ExpectedCurve(const sim::SensorModel& model, std::int64_t n) {
  AvarCurve c;
  c.sample_clock = model.sample_clock;
  c.num_samples = n;
  c.m = LogDense(n / 8, 8.0);
  for (std::int64_t m : c.m) c.tau_s.push_back(m * c.sample_clock.period_s());
  c.avar = ModelAvarOnCurve(model, c);
  return c;
}

struct Case {
  const char* name;
  sim::SensorModel model;
  double b_bound_deg_h;  // 0: no bound
};

std::vector<Case> Cases() {
  std::vector<Case> out;
  const std::pair<double, double> bumps[] = {{50.0, 3.0}, {100.0, 3.0}};  // sigma deg/h, Tc s
  for (auto [sigma, tc] : bumps) {
    sim::SensorModel m;
    m.sample_clock = SampleClock::FromRateHz(100.0);
    m.terms = {sim::WhiteRateNoise{units::DegPerSqrtHour(0.3)},
               sim::GaussMarkov{units::DegPerHour(sigma), tc}};
    out.push_back({"N + Gauss-Markov", m, sigma});
  }
  sim::SensorModel band;
  band.sample_clock = SampleClock::FromRateHz(100.0);
  band.terms = {sim::WhiteRateNoise{units::DegPerSqrtHour(0.3)},
                sim::RandomWalkRate{units::DegPerHourPerSqrtHour(2.0)}};
  band.band_limit.kind = sim::LowPassKind::kFirstOrder;
  band.band_limit.cutoff_hz = 0.5;
  out.push_back({"band-limited N + K", band, 0.0});
  return out;
}

TEST(GlsMisspecified, MisfitIsFlaggedAndFlickerDoesNotOutgrowTheBump) {
  for (const Case& c : Cases()) {
    const AvarCurve curve = ExpectedCurve(c.model, 1 << 18);
    FitOptions options;
    options.method = FitMethod::kGls;
    options.select_terms = false;
    FitSummary s;
    ASSERT_TRUE(FitAvarModel(options, curve, &s)) << c.name << ": " << s.message;
    EXPECT_LT(s.p_value, 1e-6) << c.name << ": chi2 " << s.chi2 << " on " << s.dof;
    EXPECT_TRUE(IsPoorFit(s)) << c.name << ": " << s.message;
    if (c.b_bound_deg_h > 0.0) {
      const double b = s.at(Coefficient::kB).fitted
                           ? ToDatasheetUnit(Coefficient::kB, s.at(Coefficient::kB).value_si)
                           : 0.0;
      EXPECT_LE(b, c.b_bound_deg_h) << c.name << ": B inflated beyond the bump it imitates";
    }
  }
}

}  // namespace
}  // namespace allanlab::estimators
