// The statistical comparison used by the generator tests must be able to fail: a flicker
// generator whose scale is off by 5 % (AVAR off by 10.25 %) is caught, and a correct one passes.
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/monte_carlo.h"

namespace allanlab::sim {
namespace {

using testing_support::ExactAvarStdDev;
using testing_support::MeanWithinTolerance;
using testing_support::SimulateAvar;
using testing_support::SingleTermModel;

constexpr std::int64_t kN = 1 << 14;
constexpr int kTrials = 200;

TEST(MonteCarloHelper, CatchesFivePercentFlickerScaleError) {
  const SensorModel truth = SingleTermModel(FlickerNoise{0.05}, 100.0);
  const SensorModel broken = SingleTermModel(FlickerNoise{0.05 * 1.05}, 100.0);
  const std::vector<std::int64_t> ms = testing_support::OctaveFactorsUpTo(kN / 8);
  const RecordShape shape{kN, AvarEstimatorKind::kOverlapping};
  const auto expected = truth.ExpectedAvar(ms, shape);
  const auto sd = ExactAvarStdDev(truth, kN, ms, AvarEstimatorKind::kOverlapping);
  const auto good = SimulateAvar(truth, 99, kTrials, kN, ms, AvarEstimatorKind::kOverlapping);
  const auto bad = SimulateAvar(broken, 99, kTrials, kN, ms, AvarEstimatorKind::kOverlapping);
  EXPECT_TRUE(MeanWithinTolerance(good, expected, sd, ms));
  EXPECT_FALSE(MeanWithinTolerance(bad, expected, sd, ms));
}

TEST(MonteCarloHelper, CatchesMissingSmallMExcess) {
  // Using the IEEE asymptote instead of the exact discrete value at m = 1 (flicker +44 %,
  // random walk +K^2 tau0^2/(6 tau)) must fail.
  const SensorModel model = SingleTermModel(FlickerNoise{0.05}, 100.0);
  const std::vector<std::int64_t> ms = {1, 2, 4};
  const auto sample = SimulateAvar(model, 5, kTrials, kN, ms, AvarEstimatorKind::kOverlapping);
  const auto sd = ExactAvarStdDev(model, kN, ms, AvarEstimatorKind::kOverlapping);
  std::vector<double> asymptote;
  for (std::int64_t m : ms) asymptote.push_back(model.AsymptoticAvar(m / 100.0));
  EXPECT_FALSE(MeanWithinTolerance(sample, asymptote, sd, ms));
}

}  // namespace
}  // namespace allanlab::sim
