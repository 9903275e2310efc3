// Tier c: the conformance battery every generator passes — length, determinism, thread
// invariance, scaling (2x coefficient => 4x AVAR, sample by sample 2x output), zero => zero, and
// rejection of bad parameters.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "estimators/allan_variance.h"
#include "sim/sensor_model.h"
#include "tests/support/monte_carlo.h"

namespace allanlab::sim {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

// Scales each term's amplitude coefficient (the one AVAR is quadratic in).
NoiseTerm Scaled(NoiseTerm term, double f) {
  std::visit(
      [f](auto& t) {
        using T = std::decay_t<decltype(t)>;
        if constexpr (std::is_same_v<T, QuantizationNoise>) t.q_rad *= f;
        if constexpr (std::is_same_v<T, WhiteRateNoise>) t.arw_rad_per_sqrt_s *= f;
        if constexpr (std::is_same_v<T, FlickerNoise>) t.bias_instability_rad_per_s *= f;
        if constexpr (std::is_same_v<T, FlickerGaussMarkovSum>) t.bias_instability_rad_per_s *= f;
        if constexpr (std::is_same_v<T, RandomWalkRate>) t.rrw_rad_per_s_per_sqrt_s *= f;
        if constexpr (std::is_same_v<T, RateRamp>) t.ramp_rad_per_s2 *= f;
        if constexpr (std::is_same_v<T, Harmonic>) t.amplitude_rad_per_s *= f;
        if constexpr (std::is_same_v<T, GaussMarkov>) t.sigma_rad_per_s *= f;
        if constexpr (std::is_same_v<T, RandomTelegraph>) t.amplitude_rad_per_s *= f;
        if constexpr (std::is_same_v<T, ExponentialDrift>) t.amplitude_rad_per_s *= f;
        if constexpr (std::is_same_v<T, BiasStep>) t.size_rad_per_s *= f;
        if constexpr (std::is_same_v<T, Outliers>) t.size_rad_per_s *= f;
      },
      term);
  return term;
}

// The same term with its amplitude coefficient set to a bad value.
NoiseTerm WithBadCoefficient(NoiseTerm term, double bad) {
  return std::visit(
      [bad](auto t) -> NoiseTerm {
        using T = std::decay_t<decltype(t)>;
        if constexpr (std::is_same_v<T, QuantizationNoise>) t.q_rad = bad;
        if constexpr (std::is_same_v<T, WhiteRateNoise>) t.arw_rad_per_sqrt_s = bad;
        if constexpr (std::is_same_v<T, FlickerNoise>) t.bias_instability_rad_per_s = bad;
        if constexpr (std::is_same_v<T, FlickerGaussMarkovSum>) t.bias_instability_rad_per_s = bad;
        if constexpr (std::is_same_v<T, RandomWalkRate>) t.rrw_rad_per_s_per_sqrt_s = bad;
        if constexpr (std::is_same_v<T, RateRamp>) t.ramp_rad_per_s2 = bad * kNan;
        if constexpr (std::is_same_v<T, Harmonic>) t.frequency_hz = bad;
        if constexpr (std::is_same_v<T, GaussMarkov>) t.correlation_time_s = bad;
        if constexpr (std::is_same_v<T, RandomTelegraph>) t.mean_dwell_s = bad;
        if constexpr (std::is_same_v<T, ExponentialDrift>) t.time_constant_s = bad;
        if constexpr (std::is_same_v<T, BiasStep>) t.time_s = bad;
        if constexpr (std::is_same_v<T, Outliers>) t.rate_hz = bad;
        return t;
      },
      term);
}

struct Case {
  std::string name;
  NoiseTerm term;
  bool band_limited = false;
};
std::ostream& operator<<(std::ostream& os, const Case& c) { return os << c.name; }

std::vector<Case> Cases() {
  std::vector<Case> base = {
      {"quantization", QuantizationNoise{0.01}},
      {"arw", WhiteRateNoise{0.1}},
      {"flicker", FlickerNoise{0.05}},
      {"gm_sum", FlickerGaussMarkovSum{0.05, 0.05, 50.0, 1.0}},
      {"rrw", RandomWalkRate{0.02}},
      {"ramp", RateRamp{1e-3}},
      {"harmonic", Harmonic{0.5, 7.3, std::nullopt}},
      {"gauss_markov", GaussMarkov{0.3, 2.0}},
      {"telegraph", RandomTelegraph{0.2, 3.0}},
      {"drift", ExponentialDrift{0.4, 30.0}},
      {"step", BiasStep{0.3, 12.0}},
      {"outliers", Outliers{0.5, 2.0}},
  };
  std::vector<Case> all = base;
  for (Case c : base) {
    c.name += "_bw2";
    c.band_limited = true;
    all.push_back(c);
  }
  return all;
}

SensorModel ModelOf(const Case& c, const NoiseTerm& term) {
  SensorModel model = testing_support::SingleTermModel(term, 100.0);
  if (c.band_limited) {
    model.band_limit = {LowPassKind::kButterworth2, 20.0, 4, OutputSampling::kAverage};
  }
  return model;
}

class GeneratorConformance : public ::testing::TestWithParam<Case> {};

constexpr std::int64_t kN = 5000;  // deliberately not a power of two

TEST_P(GeneratorConformance, LengthAndFiniteness) {
  const SensorModel model = ModelOf(GetParam(), GetParam().term);
  for (std::int64_t n : {std::int64_t{1}, std::int64_t{2}, std::int64_t{17}, kN}) {
    const auto y = model.Generate(1, 0, n);
    ASSERT_EQ(static_cast<std::int64_t>(y.size()), n);
    for (double v : y) ASSERT_TRUE(std::isfinite(v));
  }
}

TEST_P(GeneratorConformance, DeterministicAndTrialsDiffer) {
  const SensorModel model = ModelOf(GetParam(), GetParam().term);
  EXPECT_EQ(model.Generate(7, 3, kN), model.Generate(7, 3, kN));
  const bool deterministic_signal = std::holds_alternative<RateRamp>(GetParam().term) ||
                                    std::holds_alternative<ExponentialDrift>(GetParam().term) ||
                                    std::holds_alternative<BiasStep>(GetParam().term);
  if (!deterministic_signal) {
    EXPECT_NE(model.Generate(7, 3, kN), model.Generate(7, 4, kN));
  }
}

TEST_P(GeneratorConformance, ThreadInvariant) {
  const SensorModel model = ModelOf(GetParam(), GetParam().term);
  constexpr int kTrials = 8;
  std::vector<std::vector<double>> serial(kTrials), parallel(kTrials);
  for (int t = 0; t < kTrials; ++t) serial[t] = model.Generate(11, t, kN);
#pragma omp parallel for schedule(dynamic) num_threads(4)
  for (int t = kTrials - 1; t >= 0; --t) parallel[t] = model.Generate(11, t, kN);
  EXPECT_EQ(serial, parallel);
}

TEST_P(GeneratorConformance, DoubleCoefficientGivesFourTimesAvar) {
  const Case& c = GetParam();
  const SensorModel one = ModelOf(c, c.term);
  const SensorModel two = ModelOf(c, Scaled(c.term, 2.0));
  const auto y1 = one.Generate(5, 0, kN);
  const auto y2 = two.Generate(5, 0, kN);
  for (std::size_t i = 0; i < y1.size(); ++i) ASSERT_NEAR(y2[i], 2.0 * y1[i], 1e-12 * (1 + std::abs(y1[i])));
  const std::vector<std::int64_t> ms = {1, 4, 32, 256};
  const RecordShape shape{kN, AvarEstimatorKind::kOverlapping};
  const auto e1 = one.ExpectedAvar(ms, shape);
  const auto e2 = two.ExpectedAvar(ms, shape);
  const auto a1 = estimators::AllanVariance(y1, ms, AvarEstimatorKind::kOverlapping);
  const auto a2 = estimators::AllanVariance(y2, ms, AvarEstimatorKind::kOverlapping);
  for (std::size_t k = 0; k < ms.size(); ++k) {
    EXPECT_NEAR(e2[k], 4.0 * e1[k], 1e-12 * e2[k]) << "m=" << ms[k];
    EXPECT_NEAR(a2[k], 4.0 * a1[k], 1e-9 * a2[k]) << "m=" << ms[k];
  }
}

TEST_P(GeneratorConformance, ZeroCoefficientGivesZero) {
  const Case& c = GetParam();
  const SensorModel model = ModelOf(c, Scaled(c.term, 0.0));
  for (double v : model.Generate(5, 0, kN)) ASSERT_EQ(v, 0.0);
  const std::int64_t ms[] = {1, 8, 64};
  for (double e : model.ExpectedAvar(ms, {kN, AvarEstimatorKind::kOverlapping})) EXPECT_EQ(e, 0.0);
}

TEST_P(GeneratorConformance, RejectsBadParameters) {
  const Case& c = GetParam();
  for (double bad : {-1.0, kNan, std::numeric_limits<double>::infinity()}) {
    const SensorModel model = ModelOf(c, WithBadCoefficient(c.term, bad));
    std::string why;
    EXPECT_FALSE(model.IsValid(&why)) << c.name << " accepted " << bad;
    EXPECT_NE(why.find(std::string(TermId(c.term))), std::string::npos) << why;
  }
}

INSTANTIATE_TEST_SUITE_P(AllGenerators, GeneratorConformance, ::testing::ValuesIn(Cases()),
                         [](const auto& info) { return info.param.name; });

TEST(SensorModelValidation, RejectsCutoffAboveInternalNyquist) {
  SensorModel model = testing_support::SingleTermModel(WhiteRateNoise{0.1}, 100.0);
  model.band_limit = {LowPassKind::kFirstOrder, 250.0, 4, OutputSampling::kPoint};
  std::string why;
  EXPECT_FALSE(model.IsValid(&why));
  EXPECT_NE(why.find("Nyquist"), std::string::npos) << why;
  model.band_limit.oversampling = 8;
  EXPECT_TRUE(model.IsValid(&why)) << why;
}

TEST(SensorModelValidation, RejectsOutliersFasterThanSampling) {
  SensorModel model = testing_support::SingleTermModel(Outliers{200.0, 1.0}, 100.0);
  std::string why;
  EXPECT_FALSE(model.IsValid(&why));
}

}  // namespace
}  // namespace allanlab::sim
