// The cross-tau covariance model reproduces the exact single-tau variance of THEORY.md §2.1
// (estimators::ExactAvarMoments, itself checked against THEORY §3.2) on the diagonal, and the
// published white-noise Cov(OAVAR(4), OAVAR(8)) off it.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "estimators/exact_avar_variance.h"
#include "estimators/fit/avar_covariance.h"
#include "sim/sensor_model.h"

namespace allanlab::estimators {
namespace {

TEST(AvarCovariance, DiagonalMatchesExactVariance) {
  const double tau0 = 0.01;
  const std::int64_t n = 1 << 15;
  AvarCurve curve;
  curve.sample_period_s = tau0;
  curve.num_samples = n;
  curve.m = {1, 3, 16, 100, 700, 4096};
  for (std::int64_t m : curve.m) curve.tau_s.push_back(m * tau0), curve.avar.push_back(1.0);
  const std::vector<Coefficient> terms = {Coefficient::kQ, Coefficient::kN, Coefficient::kB,
                                          Coefficient::kK};
  const AvarCovarianceModel model(curve, terms);
  const std::array<double, 5> theta = {0.3e-4, 2.0, 0.5, 0.02, 0.0};  // Q^2, N^2, B^2, K^2, R^2
  const Eigen::MatrixXd cov = model.Covariance(theta);
  sim::SensorModel truth;
  truth.sample_rate_hz = 1.0 / tau0;
  truth.terms = {sim::QuantizationNoise{std::sqrt(theta[0])}, sim::WhiteRateNoise{std::sqrt(theta[1])},
                 sim::FlickerNoise{std::sqrt(theta[2])}, sim::RandomWalkRate{std::sqrt(theta[3])}};
  const auto r = truth.GaussianAutocovariance(n + 2 * curve.m.back());
  for (std::size_t k = 0; k < curve.size(); ++k) {
    const double exact =
        ExactAvarMoments(r, curve.m[k], {n, sim::AvarEstimatorKind::kOverlapping}).variance;
    EXPECT_NEAR(cov(k, k) / exact, 1.0, 2e-3) << "m=" << curve.m[k];
  }
}

TEST(AvarCovariance, WhiteNoiseCrossCovarianceMatchesTheory) {
  // THEORY.md §2.1: white noise, N = 1000, Cov(OAVAR(4), OAVAR(8)) = 1.296e-4 (exact recipe).
  AvarCurve curve;
  curve.sample_period_s = 1.0;
  curve.num_samples = 1000;
  curve.m = {4, 8};
  curve.tau_s = {4, 8};
  curve.avar = {1, 1};
  const std::vector<Coefficient> terms = {Coefficient::kN};
  const AvarCovarianceModel model(curve, terms);
  const Eigen::MatrixXd cov = model.Covariance({0.0, 1.0, 0.0, 0.0, 0.0});
  EXPECT_NEAR(cov(0, 1), 1.296e-4, 0.0006e-4);
}

}  // namespace
}  // namespace allanlab::estimators
