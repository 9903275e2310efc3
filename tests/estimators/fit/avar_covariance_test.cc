// The cross-tau covariance model reproduces the exact single-tau variance of docs/theory.md §3.1
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

// The model's covariance (Q, N, B, K asked) at squared coefficients theta for a record of n
// samples at 100 Hz, its diagonal checked against the exact variance of each tau's estimate.
Eigen::MatrixXd CheckedCovariance(std::int64_t n, const std::vector<std::int64_t>& ms,
                                  const std::array<double, 5>& theta) {
  const double tau0 = 0.01;
  AvarCurve curve;
  curve.sample_clock = SampleClock::FromPeriodS(tau0);
  curve.num_samples = n;
  curve.m = ms;
  for (std::int64_t m : curve.m) curve.tau_s.push_back(m * tau0), curve.avar.push_back(1.0);
  const std::vector<Coefficient> terms = {Coefficient::kQ, Coefficient::kN, Coefficient::kB,
                                          Coefficient::kK};
  const AvarCovarianceModel model(curve, terms);
  const Eigen::MatrixXd cov = model.Covariance(theta);
  sim::SensorModel truth;
  truth.sample_clock = SampleClock::FromRateHz(1.0 / tau0);
  if (theta[0] > 0.0) truth.terms.push_back(sim::QuantizationNoise{std::sqrt(theta[0])});
  if (theta[1] > 0.0) truth.terms.push_back(sim::WhiteRateNoise{std::sqrt(theta[1])});
  if (theta[2] > 0.0) truth.terms.push_back(sim::FlickerNoise{std::sqrt(theta[2])});
  if (theta[3] > 0.0) truth.terms.push_back(sim::RandomWalkRate{std::sqrt(theta[3])});
  const auto r = truth.GaussianAutocovariance(n + 2 * curve.m.back());
  for (std::size_t k = 0; k < curve.size(); ++k) {
    const double exact =
        ExactAvarMoments(r, curve.m[k], {n, sim::AvarEstimatorKind::kOverlapping}).variance;
    EXPECT_NEAR(cov(k, k) / exact, 1.0, 2e-3) << "m=" << curve.m[k];
  }
  return cov;
}

TEST(AvarCovariance, DiagonalMatchesExactVariance) {
  CheckedCovariance(1 << 15, {1, 3, 16, 100, 700, 4096},
                    {0.3e-4, 2.0, 0.5, 0.02, 0.0});  // Q^2, N^2, B^2, K^2, R^2
}

// The longest taus a record gives (m up to N/2, where the estimate has a single difference):
// the strided core sum once started at -core and stepped over k = 0 when fewer lags than the
// stride have pairs, giving a zero variance at m = N/2 and a covariance that was not positive
// definite (GLS then failed on plain white noise).
TEST(AvarCovariance, LongestTausKeepTheirVariance) {
  const Eigen::MatrixXd cov =
      CheckedCovariance(1 << 14, {1, 64, 2000, 5000, 6500, 8192}, {0.0, 1e-8, 0.0, 0.0, 0.0});
  EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(cov).info(), Eigen::Success);
}

TEST(AvarCovariance, WhiteNoiseCrossCovarianceMatchesTheory) {
  // docs/theory.md §3.1: white noise, N = 1000, Cov(OAVAR(4), OAVAR(8)) = 1.296e-4 (exact recipe).
  AvarCurve curve;
  curve.sample_clock = SampleClock::FromPeriodS(1.0);
  curve.num_samples = 1000;
  curve.m = {4, 8};
  curve.tau_s = {4, 8};
  curve.avar = {1, 1};
  const std::vector<Coefficient> terms = {Coefficient::kN};
  const AvarCovarianceModel model(curve, terms);
  const Eigen::MatrixXd cov = model.Covariance({0.0, 1.0, 0.0, 0.0, 0.0});
  EXPECT_NEAR(cov(0, 1), 1.296e-4, 0.0006e-4);
}

// Quantization alone, at taus long enough for the strided core sum (m1 + m2 >= 128): C_Q(k) is a
// few isolated spikes at k = a m1 - b m2, which a stride used to miss or over-weight (diagonal
// off by up to the stride, Q + N fits with N's sigma 4x too small). Against the exact variance
// on the diagonal and a brute-force spike sum off it: exact up to rounding.
TEST(AvarCovariance, QuantizationSpikesAreSummedExactly) {
  const double tau0 = 0.01;
  const std::int64_t n = 1 << 15;
  AvarCurve curve;
  curve.sample_clock = SampleClock::FromPeriodS(tau0);
  curve.num_samples = n;
  curve.m = {1, 100, 150, 700, 4096};
  for (std::int64_t m : curve.m) curve.tau_s.push_back(m * tau0), curve.avar.push_back(1.0);
  const std::vector<Coefficient> terms = {Coefficient::kQ};
  const AvarCovarianceModel model(curve, terms);
  const double q2 = 0.7;
  const Eigen::MatrixXd cov = model.Covariance({q2, 0.0, 0.0, 0.0, 0.0});
  sim::SensorModel truth;
  truth.sample_clock = SampleClock::FromRateHz(1.0 / tau0);
  truth.terms = {sim::QuantizationNoise{std::sqrt(q2)}};
  const auto r = truth.GaussianAutocovariance(n + 2 * curve.m.back());
  for (std::size_t k = 0; k < curve.size(); ++k) {
    const double exact =
        ExactAvarMoments(r, curve.m[k], {n, sim::AvarEstimatorKind::kOverlapping}).variance;
    EXPECT_NEAR(cov(k, k) / exact, 1.0, 1e-9) << "m=" << curve.m[k];
  }
  // D^m_s = (theta_{s+2m-1} - 2 theta_{s+m-1} + theta_{s-1}) / (m tau0), theta iid (Q^2):
  // Cov(D^{m1}_s, D^{m2}_{s+k}) = Q^2/(m1 m2 tau0^2) sum_{a,b: a m1 = k + b m2} w_a w_b, and
  // Cov(OAVAR1, OAVAR2) = sum_k n(k) C(k)^2 / (2 T1 T2), n(k) the start pairs at lag k.
  const double w[3] = {1.0, -2.0, 1.0};
  for (auto [x, y] : {std::pair<std::size_t, std::size_t>{1, 2}, {2, 3}, {1, 4}}) {
    const std::int64_t m1 = curve.m[x], m2 = curve.m[y];
    const std::int64_t t1 = n - 2 * m1 + 1, t2 = n - 2 * m2 + 1;
    double sum = 0.0;
    for (std::int64_t k = -(t1 - 1); k < t2; ++k) {
      double c = 0.0;
      for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) {
          if (a * m1 == k + b * m2) c += w[a] * w[b];
        }
      }
      if (c == 0.0) continue;
      c *= q2 / (static_cast<double>(m1) * static_cast<double>(m2) * tau0 * tau0);
      const std::int64_t pairs = std::min(t1, t2 - k) - std::max<std::int64_t>(0, -k);
      sum += static_cast<double>(pairs) * c * c;
    }
    const double brute = sum / (2.0 * static_cast<double>(t1) * static_cast<double>(t2));
    EXPECT_NEAR(cov(x, y) / brute, 1.0, 1e-9) << "m1=" << m1 << " m2=" << m2;
  }
}

}  // namespace
}  // namespace allanlab::estimators
