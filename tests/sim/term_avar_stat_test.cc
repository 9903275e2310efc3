// Tier b: for every noise term, the Monte Carlo mean of the overlapping and non-overlapping Allan
// variance at octave m = 1 .. N/8 matches the term's exact expected AVAR, including the small-m
// departures from the IEEE 952 asymptote, within z = 5 exact standard errors (docs/theory.md §3.1).
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/monte_carlo.h"

namespace allanlab::sim {
namespace {

using testing_support::ExactAvarStdDev;
using testing_support::MeanWithinTolerance;
using testing_support::OctaveFactorsUpTo;
using testing_support::SimulateAvar;
using testing_support::SingleTermModel;

struct TermCase {
  std::string name;
  NoiseTerm term;
  bool gaussian = true;  // exact SD from §2.1 applies; otherwise the Monte Carlo SD is used
  LowPassKind low_pass = LowPassKind::kNone;
};

std::ostream& operator<<(std::ostream& os, const TermCase& c) { return os << c.name; }

class TermAvarTest : public ::testing::TestWithParam<TermCase> {};

constexpr std::int64_t kSamples = 1 << 14;
constexpr int kTrials = 200;
constexpr double kRateHz = 100.0;

TEST_P(TermAvarTest, MonteCarloMeanMatchesExactExpectation) {
  const TermCase& c = GetParam();
  SensorModel model = SingleTermModel(c.term, kRateHz);
  model.band_limit.kind = c.low_pass;
  model.band_limit.cutoff_hz = 20.0;
  model.band_limit.oversampling = 4;
  std::string why;
  ASSERT_TRUE(model.IsValid(&why)) << why;
  const std::vector<std::int64_t> ms = OctaveFactorsUpTo(kSamples / 8);
  for (AvarEstimatorKind kind : {AvarEstimatorKind::kOverlapping, AvarEstimatorKind::kNonOverlapping}) {
    const RecordShape shape{kSamples, kind};
    const auto sample = SimulateAvar(model, 20261122, kTrials, kSamples, ms, kind);
    const std::vector<double> expected = model.ExpectedAvar(ms, shape);
    std::vector<double> sd;
    if (c.gaussian) {
      sd = ExactAvarStdDev(model, kSamples, ms, kind);
    } else {
      for (double v : sample.variance) sd.push_back(std::sqrt(v));
    }
    EXPECT_TRUE(MeanWithinTolerance(sample, expected, sd, ms))
        << c.name << (kind == AvarEstimatorKind::kOverlapping ? " overlapping" : " non-overlapping");
  }
}

std::vector<TermCase> Cases() {
  std::vector<TermCase> cases = {
      {"quantization", QuantizationNoise{0.01}},
      {"arw", WhiteRateNoise{0.1}},
      {"flicker", FlickerNoise{0.05}},
      {"rrw", RandomWalkRate{0.02}},
      {"gauss_markov", GaussMarkov{0.3, 2.0}},
      {"gm_sum_flicker", FlickerGaussMarkovSum{0.05, 0.05, 500.0, 1.0}},
      {"telegraph", RandomTelegraph{0.2, 3.0}, false},
      {"outliers", Outliers{0.5, 2.0}, false},
      {"harmonic_random_phase", Harmonic{0.5, 7.3, std::nullopt}, false},
  };
  for (LowPassKind kind : {LowPassKind::kFirstOrder, LowPassKind::kButterworth2}) {
    const std::string suffix = kind == LowPassKind::kFirstOrder ? "_lp1" : "_bw2";
    cases.push_back({"arw" + suffix, WhiteRateNoise{0.1}, true, kind});
    cases.push_back({"flicker" + suffix, FlickerNoise{0.05}, true, kind});
    cases.push_back({"rrw" + suffix, RandomWalkRate{0.02}, true, kind});
    cases.push_back({"gauss_markov" + suffix, GaussMarkov{0.3, 0.05}, true, kind});
    cases.push_back({"harmonic" + suffix, Harmonic{0.5, 31.0, std::nullopt}, false, kind});
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(AllTerms, TermAvarTest, ::testing::ValuesIn(Cases()),
                         [](const auto& info) { return info.param.name; });

}  // namespace
}  // namespace allanlab::sim
