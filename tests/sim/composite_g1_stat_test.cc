// docs/theory.md §7.2 / §7.4: composite model G1 (tau0 = 1, N = 2^18: quantization Q^2 = 0.25, white
// s^2 = 1, Kasdin flicker B = 0.03, random-walk step variance 9e-8). The theory code reproduces
// the published E[AVAR] and estimator SDs, and the Monte Carlo mean agrees with it.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "estimators/exact_avar_variance.h"
#include "tests/support/monte_carlo.h"

namespace allanlab::sim {
namespace {

constexpr std::int64_t kN = std::int64_t{1} << 18;

SensorModel G1() {
  SensorModel model;
  model.name = "G1";
  model.sample_clock = SampleClock::FromRateHz(1.0);
  model.terms = {QuantizationNoise{0.5}, WhiteRateNoise{1.0}, FlickerNoise{0.03},
                 RandomWalkRate{std::sqrt(9e-8)}};
  return model;
}

struct Row {
  std::int64_t m;
  double avar, sd_ovl, sd_non;
};
// docs/theory.md §7.2 (E[AVAR] with stationary-increment flicker; SDs of the two estimators).
const std::vector<Row> kTable = {
    {1, 1.750573e+00, 6.236e-03, 6.236e-03},     {4, 2.972921e-01, 1.306e-03, 2.048e-03},
    {16, 6.582913e-02, 5.732e-04, 8.942e-04},    {64, 1.620732e-02, 2.897e-04, 4.372e-04},
    {256, 4.322530e-03, 1.564e-04, 2.299e-04},   {1024, 1.405143e-03, 1.035e-04, 1.434e-04},
    {4096, 7.642095e-04, 1.177e-04, 1.439e-04},  {16384, 9.497020e-04, 3.266e-04, 3.479e-04},
    {65536, 2.378483e-03, 2.164e-03, 1.978e-03}};

TEST(CompositeG1, TheoryReproducesPublishedTable) {
  const SensorModel model = G1();
  const std::vector<double> r = model.GaussianAutocovariance(kN + 2 * 65536);
  for (const Row& row : kTable) {
    // Stationary flicker, as the table: quadratic form of the total autocovariance.
    const double stationary = AvarFromAutocovariance(row.m, r);
    EXPECT_NEAR(stationary / row.avar, 1.0, 1e-6) << "m=" << row.m;
    const auto ovl = estimators::ExactAvarMoments(r, row.m, {kN, AvarEstimatorKind::kOverlapping});
    const auto non = estimators::ExactAvarMoments(r, row.m, {kN, AvarEstimatorKind::kNonOverlapping});
    EXPECT_NEAR(std::sqrt(ovl.variance) / row.sd_ovl, 1.0, 1e-3) << "m=" << row.m;
    EXPECT_NEAR(std::sqrt(non.variance) / row.sd_non, 1.0, 1e-3) << "m=" << row.m;
  }
}

TEST(CompositeG1, MonteCarloMeanWithinThreeStandardErrors) {
  const SensorModel model = G1();
  std::vector<std::int64_t> ms;
  for (const Row& row : kTable) ms.push_back(row.m);
  constexpr int kTrials = 300;
  for (AvarEstimatorKind kind : {AvarEstimatorKind::kOverlapping, AvarEstimatorKind::kNonOverlapping}) {
    const auto sample = testing_support::SimulateAvar(model, 2024, kTrials, kN, ms, kind);
    const auto expected = model.ExpectedAvar(ms, {kN, kind});  // finite-record flicker included
    const auto sd = testing_support::ExactAvarStdDev(model, kN, ms, kind);
    EXPECT_TRUE(testing_support::MeanWithinTolerance(sample, expected, sd, ms, 3.0));
    // The spread agrees too: SD_MC / SD_theory within 1 +- 5/sqrt(2 trials) (§3.4 with z = 5).
    for (std::size_t k = 0; k < ms.size(); ++k) {
      EXPECT_NEAR(std::sqrt(sample.variance[k]) / sd[k], 1.0, 5.0 / std::sqrt(2.0 * kTrials))
          << "m=" << ms[k];
    }
  }
}

}  // namespace
}  // namespace allanlab::sim
