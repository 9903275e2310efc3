// GLS with the full model covariance: exact recovery on a noiseless curve, and on simulated
// records (fixed seeds, composite models) reported sigmas that match the actual errors: the
// z-scores (estimate - truth) / sigma of all present coefficients have an RMS within
// 1 +- 3/sqrt(2 n_z) of 1 (the SD of the RMS of n_z standard normals is 1/sqrt(2 n_z)) and none
// beyond 4.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "estimators/allan_variance.h"
#include "estimators/avar.h"
#include "estimators/fit/avar_curve.h"
#include "estimators/fit/noise_coefficient.h"
#include "estimators/fit/fit_avar_model.h"
#include "sim/sensor_model.h"
#include "sim/units.h"
#include "tests/support/fit_curves.h"

namespace allanlab::estimators {
namespace {

using testing_support::Curve;
using testing_support::LogDense;

struct Case {
  const char* name;
  double q_urad, n_deg_rt_h, b_deg_h, k_deg_h_rt_h;
};

TEST(GlsFit, RecoversPresentCoefficientsWithHonestSigmas) {
  const double rate = 100.0;
  const std::int64_t n = 1 << 18;
  const auto ms = LogDense(n / 8, 8.0);
  const Case cases[] = {{"N+B+K", 0.0, 0.2, 3.0, 20.0}, {"Q+N+B", 20.0, 0.1, 1.0, 0.0}};
  std::vector<double> z;
  for (const Case& c : cases) {
    sim::SensorModel model;
    model.sample_clock = SampleClock::FromRateHz(rate);
    const std::pair<Coefficient, double> truth[] = {{Coefficient::kQ, c.q_urad},
                                                    {Coefficient::kN, c.n_deg_rt_h},
                                                    {Coefficient::kB, c.b_deg_h},
                                                    {Coefficient::kK, c.k_deg_h_rt_h}};
    FitOptions options;
    options.method = FitMethod::kGls;
    options.select_terms = false;  // the sigmas of a fixed model are under test here
    options.terms.clear();
    for (auto [coef, value] : truth) {
      if (value == 0.0) continue;
      model.terms.push_back(TermFor(coef, FromDatasheetUnit(coef, value)));
      options.terms.push_back(coef);
    }
    FitSummary exact;
    ASSERT_TRUE(FitAvarModel(
        options,
        Curve(rate, n, ms, model.ExpectedAvar(ms, {n, sim::AvarEstimatorKind::kOverlapping})),
        &exact))
        << exact.message;
    for (auto [coef, value] : truth) {
      if (value == 0.0) continue;
      EXPECT_NEAR(ToDatasheetUnit(coef, exact.at(coef).value_si) / value, 1.0, 1e-5) << c.name;
    }
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
      const auto y = model.Generate(seed, 0, n);
      FitSummary s;
      ASSERT_TRUE(FitAvarModel(
          options, Curve(rate, n, ms, AllanVariance(y, ms, sim::AvarEstimatorKind::kOverlapping)),
          &s))
          << s.message;
      EXPECT_TRUE(s.converged) << c.name << " seed " << seed << ": " << s.message;
      for (auto [coef, value] : truth) {
        if (value == 0.0) continue;
        const auto& e = s.at(coef);
        z.push_back((ToDatasheetUnit(coef, e.value_si) - value) /
                    ToDatasheetUnit(coef, e.sigma_si));
        EXPECT_LT(std::abs(z.back()), 4.0)
            << c.name << " " << CoefficientId(coef) << " seed " << seed;
      }
    }
  }
  double sum2 = 0.0;
  for (double v : z) sum2 += v * v;
  const double rms = std::sqrt(sum2 / z.size());
  EXPECT_NEAR(rms, 1.0, 3.0 / std::sqrt(2.0 * z.size())) << z.size() << " z-scores";
}

}  // namespace
}  // namespace allanlab::estimators

namespace allanlab::estimators {
namespace {

// Term selection: fitting all five terms to N + B + K records in which each term dominates its
// own tau range (N below 3 s, B from 3 to 100 s, K from 100 s to the longest tau, 330 s) keeps
// N, B, K and drops Q and R. (Where a term dominates no tau range — e.g. B = 3 deg/h with
// N = 0.2 deg/sqrt(h), K = 20 deg/h/sqrt(h) — some records do not support it and selection
// rightly drops it.)
TEST(GlsFit, TermSelectionDropsAbsentTerms) {
  const double rate = 100.0;
  const std::int64_t n = 1 << 18;
  const auto ms = LogDense(n / 8, 8.0);
  sim::SensorModel model;
  model.sample_clock = SampleClock::FromRateHz(rate);
  model.terms = {TermFor(Coefficient::kN, FromDatasheetUnit(Coefficient::kN, 0.115)),
                 TermFor(Coefficient::kB, FromDatasheetUnit(Coefficient::kB, 6.0)),
                 TermFor(Coefficient::kK, FromDatasheetUnit(Coefficient::kK, 41.0))};
  FitOptions options;
  options.method = FitMethod::kGls;
  int correct = 0, fits = 0;
  for (std::uint64_t seed = 21; seed <= 24; ++seed) {
    const auto y = model.Generate(seed, 0, n);
    FitSummary s;
    ASSERT_TRUE(FitAvarModel(
        options, Curve(rate, n, ms, AllanVariance(y, ms, sim::AvarEstimatorKind::kOverlapping)),
        &s))
        << s.message;
    ++fits;
    const bool ok = s.at(Coefficient::kN).fitted && s.at(Coefficient::kB).fitted &&
                    s.at(Coefficient::kK).fitted && !s.at(Coefficient::kQ).fitted &&
                    !s.at(Coefficient::kR).fitted;
    correct += ok;
    EXPECT_TRUE(ok) << "seed " << seed << ": Q " << s.at(Coefficient::kQ).note << "; N "
                    << s.at(Coefficient::kN).note << "; B " << s.at(Coefficient::kB).note << "; K "
                    << s.at(Coefficient::kK).note << "; R " << s.at(Coefficient::kR).note;
  }
  EXPECT_EQ(correct, fits);
}

// Without profile ranges a fit gives the same values, sigmas and chi2 (the ranges are read from
// the fitted problem, never fed back), and leaves the intervals and upper limits unset.
TEST(GlsFit, ProfileRangesDoNotMoveTheFit) {
  const double rate = 100.0;
  const std::int64_t n = 1 << 16;
  sim::SensorModel model;
  model.sample_clock = SampleClock::FromRateHz(rate);
  model.terms.push_back(TermFor(Coefficient::kN, FromDatasheetUnit(Coefficient::kN, 0.2)));
  model.terms.push_back(TermFor(Coefficient::kK, FromDatasheetUnit(Coefficient::kK, 20.0)));
  const auto record = model.Generate(5, 0, n);
  AvarOptions ao;
  ao.statistic = Statistic::kAllanOverlapping;
  ao.sample_clock = model.sample_clock;
  ao.taus.kind = TauGridKind::kLogDense;
  AvarSummary summary;
  ASSERT_TRUE(ComputeAvar(ao, record, &summary)) << summary.message;
  const AvarCurve curve = CurveFromSummary(summary);
  FitOptions with;
  with.method = FitMethod::kGls;
  FitOptions without = with;
  without.profile_ranges = false;
  FitSummary a, b;
  ASSERT_TRUE(FitAvarModel(with, curve, &a)) << a.message;
  ASSERT_TRUE(FitAvarModel(without, curve, &b)) << b.message;
  EXPECT_EQ(a.chi2, b.chi2);
  bool some_range = false;
  for (Coefficient c : kAllCoefficients) {
    EXPECT_EQ(a.at(c).fitted, b.at(c).fitted) << CoefficientId(c);
    EXPECT_EQ(a.at(c).value_si, b.at(c).value_si) << CoefficientId(c);
    EXPECT_EQ(a.at(c).sigma_si, b.at(c).sigma_si) << CoefficientId(c);
    EXPECT_FALSE(b.at(c).has_intervals || b.at(c).has_upper_limit) << CoefficientId(c);
    some_range = some_range || a.at(c).has_intervals;
  }
  EXPECT_TRUE(some_range);
}

}  // namespace
}  // namespace allanlab::estimators
