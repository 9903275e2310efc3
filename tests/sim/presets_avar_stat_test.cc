// Every shipped preset (composite, band-limited models) generates records whose mean overlapping
// Allan variance matches the model's exact expectation at octave m = 1 .. N/8. Presets with
// output quantizers have an approximate theory; their tolerance uses the Monte Carlo spread and
// the check is reported, not skipped.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sim/sensor_spec.h"
#include "tests/support/monte_carlo.h"

namespace allanlab::sim {
namespace {

class PresetAvar : public ::testing::TestWithParam<std::string> {};

TEST_P(PresetAvar, MonteCarloMeanMatchesExactExpectation) {
  SensorModel model;
  std::string why;
  ASSERT_TRUE(LoadPreset(GetParam(), &model, &why)) << why;
  constexpr std::int64_t kN = 1 << 14;
  constexpr int kTrials = 150;
  const std::vector<std::int64_t> ms = testing_support::OctaveFactorsUpTo(kN / 8);
  const auto kind = AvarEstimatorKind::kOverlapping;
  const auto sample = testing_support::SimulateAvar(model, 31, kTrials, kN, ms, kind);
  const auto expected = model.ExpectedAvar(ms, {kN, kind});
  std::vector<double> sd;
  if (model.ExpectedAvarIsExact()) {
    sd = testing_support::ExactAvarStdDev(model, kN, ms, kind);
  } else {
    for (double v : sample.variance) sd.push_back(std::sqrt(v));
  }
  EXPECT_TRUE(testing_support::MeanWithinTolerance(sample, expected, sd, ms)) << GetParam();
}

INSTANTIATE_TEST_SUITE_P(AllPresets, PresetAvar, ::testing::ValuesIn(PresetNames()),
                         [](const auto& info) { return info.param; });

}  // namespace
}  // namespace allanlab::sim
