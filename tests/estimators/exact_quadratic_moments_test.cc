// ModelStatisticMoments (exact_quadratic_moments.h, exact_edf.h) against an independent brute
// force: the estimator code itself, applied to basis records, gives the matrix A of its quadratic
// form y'Ay (polarisation), and E = tr(A Sigma), Var = 2 tr((A Sigma)^2) with Sigma the
// record's covariance written out here from the generator's definition (docs/theory.md §2):
// white: s^2 I; discrete random walk y_k = sum_{l<=k} w_l: s_w^2 (min(i,j) + 1) (the true,
// non-stationary covariance, not the generalised R the fast path uses); quantization
// y_k = theta_k - theta_{k-1}: Q^2 (2, -1) tridiagonal; stationary-increment Kasdin flicker: the
// generalised Toeplitz R(k) = -(2/pi) sum_{i<=k} 1/(2i-1). Everything in double with N = 40, so
// the tolerance is 1e-9 relative (rounding only).
#include "estimators/exact_edf.h"

#include <cmath>
#include <cstdint>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "estimators/avar.h"
#include "estimators/exact_quadratic_moments.h"
#include "tests/support/monte_carlo.h"

namespace allanlab::estimators {
namespace {

constexpr std::int64_t kN = 40;

double Estimate(Statistic s, std::int64_t m, const std::vector<double>& y) {
  AvarOptions options;
  options.statistic = s;
  options.sample_clock = SampleClock::FromPeriodS(1.0);
  options.taus.kind = TauGridKind::kExplicit;
  options.taus.explicit_taus_s = {static_cast<double>(m)};
  options.confidence_method = ConfidenceMethod::kNone;
  AvarSummary summary;
  EXPECT_TRUE(ComputeAvar(options, y, &summary)) << summary.message;
  EXPECT_EQ(summary.points.size(), 1u);
  return summary.points.empty() ? 0.0 : summary.points[0].value;
}

// A_ij = (q(e_i + e_j) - q(e_i) - q(e_j)) / 2 with q the estimate.
Eigen::MatrixXd QuadraticForm(Statistic s, std::int64_t m) {
  std::vector<double> y(kN, 0.0);
  Eigen::VectorXd diag(kN);
  for (std::int64_t i = 0; i < kN; ++i) {
    y[i] = 1.0;
    diag(i) = Estimate(s, m, y);
    y[i] = 0.0;
  }
  Eigen::MatrixXd a(kN, kN);
  for (std::int64_t i = 0; i < kN; ++i) {
    a(i, i) = diag(i);
    for (std::int64_t j = i + 1; j < kN; ++j) {
      y[i] = y[j] = 1.0;
      a(i, j) = a(j, i) = 0.5 * (Estimate(s, m, y) - diag(i) - diag(j));
      y[i] = y[j] = 0.0;
    }
  }
  return a;
}

Eigen::MatrixXd Covariance(const std::function<double(std::int64_t, std::int64_t)>& entry) {
  Eigen::MatrixXd sigma(kN, kN);
  for (std::int64_t i = 0; i < kN; ++i) {
    for (std::int64_t j = 0; j < kN; ++j) sigma(i, j) = entry(i, j);
  }
  return sigma;
}

double FlickerR(std::int64_t k) {
  double sum = 0.0;
  for (std::int64_t i = 1; i <= std::llabs(k); ++i) sum += 1.0 / (2.0 * static_cast<double>(i) - 1.0);
  return -(2.0 / std::numbers::pi) * sum;
}

struct Case {
  std::string name;
  sim::NoiseTerm term;
  Eigen::MatrixXd sigma;
};

std::vector<Case> Cases() {
  return {
      {"white", sim::WhiteRateNoise{1.0}, Covariance([](auto i, auto j) { return i == j ? 1.0 : 0.0; })},
      {"random walk", sim::RandomWalkRate{1.0},
       Covariance([](auto i, auto j) { return static_cast<double>(std::min(i, j) + 1); })},
      {"quantization", sim::QuantizationNoise{1.0},
       Covariance([](auto i, auto j) { return i == j ? 2.0 : (std::llabs(i - j) == 1 ? -1.0 : 0.0); })},
      {"flicker", sim::FlickerNoise{1.0}, Covariance([](auto i, auto j) { return FlickerR(i - j); })},
  };
}

TEST(ExactQuadraticMoments, MatchBruteForceTraceOfTheEstimatorsQuadraticForm) {
  const std::vector<Case> cases = Cases();
  for (Statistic s : {Statistic::kAllanNonOverlapping, Statistic::kAllanOverlapping,
                      Statistic::kModifiedAllan, Statistic::kHadamardNonOverlapping,
                      Statistic::kHadamardOverlapping}) {
    for (std::int64_t m : {1, 2, 3, 5, 8, 13}) {
      if (m > MaxAveragingFactor(s, kN)) continue;
      const Eigen::MatrixXd a = QuadraticForm(s, m);
      for (const Case& c : cases) {
        const Eigen::MatrixXd as = a * c.sigma;
        const double mean = as.trace();
        const double variance = 2.0 * (as * as).trace();
        const std::int64_t ms[] = {m};
        const AvarMoments got =
            ModelStatisticMoments(testing_support::SingleTermModel(c.term, 1.0), s, ms, kN)[0];
        const std::string where =
            std::string(StatisticId(s)) + " m=" + std::to_string(m) + " " + c.name;
        EXPECT_NEAR(got.mean, mean, 1e-9 * std::abs(mean)) << where;
        EXPECT_NEAR(got.variance, variance, 1e-9 * std::abs(variance)) << where;
      }
    }
  }
}

// The filters' own normalisation: on a unit white record the modified and Hadamard filters have
// the closed-form expectations of docs/theory.md §2.2 (MVAR = s^2 (m^2 + 1) / (2 m^3), HVAR = s^2 / m).
TEST(ExactQuadraticMoments, FilterNormalisationMatchesWhiteNoiseClosedForms) {
  for (std::int64_t m : {1, 2, 7, 30}) {
    double sq_mod = 0.0, sq_had = 0.0;
    for (double c : DifferenceFilter(Statistic::kModifiedAllan, m)) sq_mod += c * c;
    for (double c : DifferenceFilter(Statistic::kHadamardOverlapping, m)) sq_had += c * c;
    const double md = static_cast<double>(m);
    EXPECT_NEAR(sq_mod, (md * md + 1.0) / (2.0 * md * md * md), 1e-14) << "m=" << m;
    EXPECT_NEAR(sq_had, 1.0 / md, 1e-14) << "m=" << m;
  }
  EXPECT_TRUE(DifferenceFilter(Statistic::kTotal, 4).empty());
  EXPECT_TRUE(DifferenceFilter(Statistic::kAllanOverlapping, 0).empty());
}

TEST(ExactQuadraticMoments, UncoveredStatisticsAndFactorsGiveZeroMoments) {
  const sim::SensorModel model = testing_support::SingleTermModel(sim::WhiteRateNoise{1.0}, 1.0);
  const std::int64_t ms[] = {0, 4, 200};
  const auto total = ModelStatisticMoments(model, Statistic::kTotal, ms, 300);
  for (const AvarMoments& m : total) EXPECT_EQ(m.variance, 0.0);
  const auto hadamard = ModelStatisticMoments(model, Statistic::kHadamardOverlapping, ms, 300);
  EXPECT_EQ(hadamard[0].variance, 0.0);
  EXPECT_GT(hadamard[1].variance, 0.0);
  EXPECT_EQ(hadamard[2].edf(), 0.0);  // m = 200 > 300 / 3
}

}  // namespace
}  // namespace allanlab::estimators
