// The parametric bootstrap's sigma (parametric_bootstrap.h) against the truth, fixed seeds.
// (1) N + H, where the covariance sigma of the harmonic amplitude is known to be several times too
// small (parametric_recovery_stat_test.cc): the bootstrap sigma from one record must agree with
// the empirical spread of Omega0 over independent records. Both are sample standard deviations,
// so under agreement s_boot^2 / s_emp^2 ~ F(B - 1, S - 1); the test accepts the central
// 1 - 2e-4 of that F distribution (false-fail rate 2e-4, ignoring the few-% difference between
// sigma at the fitted and at the true model), and checks that the covariance sigma falls outside
// the same band, so the band is tight enough to catch what the bootstrap is for.
// (2) N + B, a Gaussian model that Omega describes: the bootstrap sigma must agree with the
// covariance sigma within the chi-square band of B - 1 degrees of freedom (same rate).
#include <gtest/gtest.h>

#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/fisher_f.hpp>
#include <cmath>
#include <vector>

#include "estimators/allan_variance.h"
#include "estimators/fit/fit_avar_model.h"
#include "estimators/fit/parametric_fit.h"
#include "sim/units.h"
#include "tests/support/fit_curves.h"

namespace allanlab::estimators {
namespace {

using testing_support::Curve;
using testing_support::LogDense;

constexpr double kRate = 100.0;
constexpr std::int64_t kSamples = 1 << 18;
constexpr double kTail = 1e-4;  // per side

double SampleSd(const std::vector<double>& v) {
  double mean = 0.0;
  for (double x : v) mean += x;
  mean /= static_cast<double>(v.size());
  double ss = 0.0;
  for (double x : v) ss += (x - mean) * (x - mean);
  return std::sqrt(ss / static_cast<double>(v.size() - 1));
}

TEST(ParametricBootstrap, HarmonicAmplitudeSigmaMatchesEmpiricalSpread) {
  const auto ms = LogDense(kSamples / 8, 8.0);
  const double omega0 = units::DegPerHour(40.0), f0 = 0.2;
  sim::SensorModel truth;
  truth.sample_clock = SampleClock::FromRateHz(kRate);
  truth.terms = {TermFor(Coefficient::kN, FromDatasheetUnit(Coefficient::kN, 0.3)),
                 sim::Harmonic{omega0, f0, std::nullopt}};
  ParametricFitOptions options;
  options.method = FitMethod::kGls;
  options.terms = {Coefficient::kN};
  options.extra = {std::shared_ptr<const ParametricTerm>(MakeHarmonicTerm())};
  auto fit = [&](std::uint64_t seed, const ParametricFitOptions& o, ParametricFitSummary* s) {
    const auto y = truth.Generate(seed, 0, kSamples);
    return FitAvarModelWithTerms(
        o, Curve(kRate, kSamples, ms, AllanVariance(y, ms, sim::AvarEstimatorKind::kOverlapping)), s);
  };

  constexpr int kSeeds = 30;
  std::vector<double> amplitudes;
  for (std::uint64_t seed = 1; seed <= kSeeds; ++seed) {
    ParametricFitSummary s;
    ASSERT_TRUE(fit(1000 + seed, options, &s)) << s.base.message;
    ASSERT_TRUE(s.extra[0].fitted) << s.extra[0].note;
    amplitudes.push_back(s.extra[0].value_si[0]);
  }
  const double empirical = SampleSd(amplitudes);

  ParametricFitOptions boot = options;
  boot.uncertainty = FitUncertainty::kBootstrap;
  boot.bootstrap.trials = 60;
  boot.bootstrap.seed = 7;
  ParametricFitSummary s;
  ASSERT_TRUE(fit(1, boot, &s)) << s.base.message;
  ASSERT_EQ(s.base.uncertainty, FitUncertainty::kBootstrap) << s.base.message;
  ASSERT_GE(s.base.bootstrap_used, 55) << s.base.message;
  const double bootstrap = s.extra[0].sigma_si[0];
  const double covariance = s.extra[0].covariance_sigma_si[0];

  const boost::math::fisher_f f(s.base.bootstrap_used - 1, kSeeds - 1);
  const double lo = std::sqrt(boost::math::quantile(f, kTail));
  const double hi = std::sqrt(boost::math::quantile(f, 1.0 - kTail));
  const double ratio = bootstrap / empirical;
  EXPECT_GT(ratio, lo) << "bootstrap " << bootstrap << " empirical " << empirical;
  EXPECT_LT(ratio, hi) << "bootstrap " << bootstrap << " empirical " << empirical;
  // What the bootstrap is for: the covariance sigma fails the same test.
  EXPECT_LT(covariance / empirical, lo) << "covariance " << covariance << " empirical " << empirical;
  std::printf("Omega0 sigma: bootstrap %.4g, covariance %.4g, empirical %.4g (%d seeds); band "
              "[%.3f, %.3f]\n",
              bootstrap, covariance, empirical, kSeeds, lo, hi);
}

TEST(ParametricBootstrap, GaussianModelBootstrapMatchesCovariance) {
  const auto ms = LogDense(kSamples / 8, 8.0);
  sim::SensorModel truth;
  truth.sample_clock = SampleClock::FromRateHz(kRate);
  truth.terms = {TermFor(Coefficient::kN, FromDatasheetUnit(Coefficient::kN, 0.2)),
                 TermFor(Coefficient::kB, FromDatasheetUnit(Coefficient::kB, 3.0))};
  FitOptions options;
  options.method = FitMethod::kGls;
  options.terms = {Coefficient::kN, Coefficient::kB};
  options.select_terms = false;
  options.uncertainty = FitUncertainty::kBootstrap;
  options.bootstrap.trials = 60;
  options.bootstrap.seed = 3;
  const auto y = truth.Generate(11, 0, kSamples);
  FitSummary s;
  ASSERT_TRUE(FitAvarModel(
      options, Curve(kRate, kSamples, ms, AllanVariance(y, ms, sim::AvarEstimatorKind::kOverlapping)),
      &s))
      << s.message;
  ASSERT_EQ(s.uncertainty, FitUncertainty::kBootstrap) << s.message;
  ASSERT_EQ(s.bootstrap_used, 60) << s.message;
  const boost::math::chi_squared chi2(s.bootstrap_used - 1);
  const double lo = std::sqrt(boost::math::quantile(chi2, kTail) / (s.bootstrap_used - 1));
  const double hi = std::sqrt(boost::math::quantile(chi2, 1.0 - kTail) / (s.bootstrap_used - 1));
  for (Coefficient c : {Coefficient::kN, Coefficient::kB}) {
    const CoefficientEstimate& e = s.at(c);
    ASSERT_TRUE(e.fitted);
    const double ratio = e.sigma_si / e.covariance_sigma_si;
    EXPECT_GT(ratio, lo) << CoefficientId(c);
    EXPECT_LT(ratio, hi) << CoefficientId(c);
    // The bootstrap bias of an (asymptotically unbiased) GLS estimate is within a few of its own
    // standard errors sigma / sqrt(B).
    EXPECT_LT(std::abs(e.bootstrap_bias_si), 5.0 * e.sigma_si / std::sqrt(60.0)) << CoefficientId(c);
    std::printf("%s sigma: bootstrap %.4g, covariance %.4g (ratio %.3f, band [%.3f, %.3f])\n",
                std::string(CoefficientId(c)).c_str(), e.sigma_si, e.covariance_sigma_si, ratio, lo, hi);
  }
}

}  // namespace
}  // namespace allanlab::estimators
