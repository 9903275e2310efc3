// The independent generator against its own closed forms (independent/allan_forms.h): the
// Monte Carlo mean of the overlapping AVAR over `kTrials` records at octave m = 1 .. N/8 must lie
// within z = 5 standard errors of the expected value, the standard error from the spread of the
// trials themselves (valid for the non-Gaussian components too). testing_support::kZ = 5: a
// false failure about once in 1.7 million comparisons; ~13 comparisons per case.
// Each case also names the deliberate error it must catch (the same check with the expected value
// off by that much must fail), so a tolerance too wide to see a wrong form fails the test.
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "estimators/allan_variance.h"
#include "independent/allan_forms.h"
#include "independent/generate.h"
#include "tests/support/monte_carlo.h"

namespace allanlab::independent {
namespace {

using testing_support::AvarSample;
using testing_support::MeanWithinTolerance;

constexpr std::int64_t kSamples = 1 << 14;
constexpr int kTrials = 120;

struct Case {
  std::string name;
  std::function<void(Recipe*)> set;
  double wrong_factor = 1.25;  // an expected curve off by this factor at every m must be rejected
};
std::ostream& operator<<(std::ostream& os, const Case& c) { return os << c.name; }

AvarSample Simulate(const Recipe& r, std::span<const std::int64_t> ms) {
  AvarSample s;
  s.trials = kTrials;
  s.mean.assign(ms.size(), 0.0);
  std::vector<double> sum2(ms.size(), 0.0);
  for (int t = 0; t < kTrials; ++t) {
    const std::vector<double> y = Generate(r, kSamples, 20261124, static_cast<std::uint64_t>(t));
    const std::vector<double> a = estimators::AllanVariance(y, ms, estimators::AvarEstimatorKind::kOverlapping);
    for (std::size_t i = 0; i < ms.size(); ++i) {
      s.mean[i] += a[i] / kTrials;
      sum2[i] += a[i] * a[i];
    }
  }
  s.variance.resize(ms.size());
  for (std::size_t i = 0; i < ms.size(); ++i) {
    s.variance[i] = (sum2[i] - kTrials * s.mean[i] * s.mean[i]) / (kTrials - 1);
  }
  return s;
}

class IndependentAvarTest : public ::testing::TestWithParam<Case> {};

TEST_P(IndependentAvarTest, MonteCarloMeanMatchesClosedForm) {
  const Case& c = GetParam();
  Recipe r;
  r.rate_hz = 100.0;
  c.set(&r);
  std::string why;
  ASSERT_TRUE(r.IsValid(kSamples, &why)) << why;
  const std::vector<std::int64_t> ms = estimators::OctaveAveragingFactors(kSamples / 8);
  const AvarSample s = Simulate(r, ms);
  const std::vector<double> expected = ExpectedOavar(r, ms, kSamples);
  std::vector<double> sd;
  for (double v : s.variance) sd.push_back(std::sqrt(v));
  EXPECT_TRUE(MeanWithinTolerance(s, expected, sd, ms)) << c.name;
  std::vector<double> wrong = expected;
  for (double& w : wrong) w *= c.wrong_factor;
  EXPECT_FALSE(MeanWithinTolerance(s, wrong, sd, ms)) << c.name << ": a curve off by " << c.wrong_factor
                                                       << "x passes too";
}

std::vector<Case> Cases() {
  std::vector<Case> cases = {
      {"white_gaussian", [](Recipe* r) { r->noise.arw_rad_per_sqrt_s = 1e-3; }, 1.05},
      {"white_student_t", [](Recipe* r) {
         r->noise.arw_rad_per_sqrt_s = 1e-3;
         r->noise.white_law = WhiteLaw::kStudentT;
         r->noise.student_t_dof = 6;
       }, 1.05},
      {"white_laplace", [](Recipe* r) {
         r->noise.arw_rad_per_sqrt_s = 1e-3;
         r->noise.white_law = WhiteLaw::kLaplace;
       }, 1.05},
      {"flicker", [](Recipe* r) { r->noise.flicker_floor_rad_per_s = 1e-4; }},
      {"rate_random_walk", [](Recipe* r) { r->noise.rrw_rad_per_s_per_sqrt_s = 1e-4; }},
      {"ramp_with_white", [](Recipe* r) {
         r->noise.arw_rad_per_sqrt_s = 1e-3;
         r->noise.ramp_rad_per_s2 = 2e-6;
       }},
      {"gauss_markov", [](Recipe* r) { r->gauss_markov = GaussMarkov{1e-3, 0.5}; }},
      {"gauss_markov_long", [](Recipe* r) { r->gauss_markov = GaussMarkov{1e-3, 20.0}; }},
      {"telegraph", [](Recipe* r) { r->telegraph = Telegraph{1e-3, 1.0}; }},
      {"sinusoid_random_phase", [](Recipe* r) {
         r->noise.arw_rad_per_sqrt_s = 1e-4;
         r->sinusoid = Sinusoid{1e-3, 3.3, std::nullopt};
       }},
      {"resonance", [](Recipe* r) { r->resonance = Resonance{1e-3, 22.0, 0.05}; }},
      {"bias_step_with_white", [](Recipe* r) {
         r->noise.arw_rad_per_sqrt_s = 1e-4;
         r->bias_step = BiasStep{-2e-4, 60.0};
       }},
      {"warmup_drift_with_white", [](Recipe* r) {
         r->noise.arw_rad_per_sqrt_s = 1e-4;
         r->warmup_drift = WarmupDrift{1e-3, 20.0};
       }},
      {"spikes_two_sided", [](Recipe* r) {
         r->noise.arw_rad_per_sqrt_s = 1e-4;
         r->spikes = Spikes{1.0, 3e-3, 6.0, false};
       }},
      {"spikes_one_sided", [](Recipe* r) {
         r->noise.arw_rad_per_sqrt_s = 1e-4;
         r->spikes = Spikes{5.0, 3e-3, 8.0, true};
       }},
      {"rate_quantizer_dithered", [](Recipe* r) {
         r->noise.arw_rad_per_sqrt_s = 1e-4;
         r->noise.bias_rad_per_s = 3.7e-4;
         r->rate_quantizer = RateQuantizer{2e-3, true};
       }},
      {"rate_quantizer_busy", [](Recipe* r) {
         r->noise.arw_rad_per_sqrt_s = 2e-4;  // 2 mrad/s per sample: 2 LSB
         r->noise.bias_rad_per_s = 3.7e-4;
         r->rate_quantizer = RateQuantizer{1e-3, false};
       }},
      {"angle_quantizer_busy", [](Recipe* r) {
         r->noise.arw_rad_per_sqrt_s = 1e-3;  // angle steps of 1e-4 rad per sample: 3 LSB
         r->noise.bias_rad_per_s = 1e-2;
         r->angle_quantizer = AngleQuantizer{3e-5};
       }},
  };
  const std::pair<const char*, LowPassDesign> designs[] = {
      {"lp1_impulse_invariant", LowPassDesign::kFirstOrderImpulseInvariant},
      {"lp1_bilinear", LowPassDesign::kFirstOrderBilinear},
      {"lp2_impulse_invariant", LowPassDesign::kSecondOrderImpulseInvariant},
      {"lp2_bilinear", LowPassDesign::kSecondOrderBilinear},
  };
  for (const auto& [name, design] : designs) {
    for (Decimation d : {Decimation::kPoint, Decimation::kAverage}) {
      cases.push_back({std::string(name) + (d == Decimation::kPoint ? "_point" : "_average"), [design, d](Recipe* r) {
                         r->noise.arw_rad_per_sqrt_s = 1e-3;
                         r->low_pass = LowPass{design, 12.0, 4, d, 3};
                       }, 1.05});
    }
  }
  cases.push_back({"cic3", [](Recipe* r) {
                     r->noise.arw_rad_per_sqrt_s = 1e-3;
                     r->low_pass = LowPass{LowPassDesign::kCic, 0.0, 8, Decimation::kPoint, 3};
                   }, 1.05});
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Components, IndependentAvarTest, ::testing::ValuesIn(Cases()),
                         [](const auto& info) { return info.param.name; });

TEST(IndependentGenerator, SameSeedSameSamplesAndComponentsKeepTheirStreams) {
  Recipe r;
  r.noise.arw_rad_per_sqrt_s = 1e-3;
  r.noise.flicker_floor_rad_per_s = 1e-4;
  const auto a = Generate(r, 4096, 5, 2), b = Generate(r, 4096, 5, 2), c = Generate(r, 4096, 5, 3);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  // Adding a deterministic step changes nothing else.
  Recipe s = r;
  s.bias_step = BiasStep{1.0, 20.0};
  const auto d = Generate(s, 4096, 5, 2);
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_DOUBLE_EQ(d[i] - a[i], i >= 2000 ? 1.0 : 0.0) << i;
}

TEST(IndependentGenerator, RefusesImpossibleRecipes) {
  Recipe r;
  std::string why;
  r.low_pass = LowPass{LowPassDesign::kSecondOrderBilinear, 500.0, 8, Decimation::kPoint, 3};
  EXPECT_FALSE(r.IsValid(1000, &why));
  EXPECT_NE(why.find("Nyquist"), std::string::npos) << why;
  r = Recipe{};
  r.resonance = Resonance{1e-3, 60.0, 0.05};
  EXPECT_FALSE(r.IsValid(1000, &why));
  r = Recipe{};
  r.noise.arw_rad_per_sqrt_s = std::nan("");
  EXPECT_FALSE(r.IsValid(1000, &why));
  EXPECT_THROW(Generate(r, 1000, 1, 0), std::invalid_argument);
  r = Recipe{};
  EXPECT_FALSE(r.IsValid(8, &why));
}

}  // namespace
}  // namespace allanlab::independent
