// The independent benchmark's draw (experiments/diagnosis/independent_case.h): deterministic, the
// layout's counts, strengths solved into their class, and the strength scale checked on two
// effects whose visibility has a closed form of its own.
#include <cmath>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "experiments/diagnosis/independent_case.h"
#include "independent/generate.h"

namespace allanlab::experiments {
namespace {

IndependentDrawOptions Short() {
  IndependentDrawOptions o;
  o.min_duration_s = 300.0;
  o.max_duration_s = 600.0;
  return o;
}

// The excess kurtosis of a record's first differences as a z against its Gaussian null sd
// sqrt(24 / n): what the strength's kurtosis_z predicts.
double IncrementKurtosisZ(const std::vector<double>& y) {
  double m2 = 0.0, m4 = 0.0;
  for (std::size_t i = 1; i < y.size(); ++i) {
    const double x = y[i] - y[i - 1];
    m2 += x * x;
    m4 += x * x * x * x;
  }
  const auto n = static_cast<double>(y.size() - 1);
  m2 /= n;
  m4 /= n;
  return (m4 / (m2 * m2) - 3.0) / std::sqrt(24.0 / n);
}

TEST(IndependentCase, LayoutCountsAndDeterminism) {
  std::map<std::string, int> count;
  const int n = 20;
  int on_target = 0, solvable = 0;
  for (int i = 0; i < n; ++i) {
    IndependentCase a, b;
    std::string why;
    ASSERT_TRUE(DrawIndependentCase(Short(), 11, i, &a, &why)) << why;
    if (i < 3) ASSERT_TRUE(DrawIndependentCase(Short(), 11, i, &b, &why)) << why; else b = a;
    EXPECT_EQ(a.descriptor.params_text, b.descriptor.params_text);
    EXPECT_EQ(a.num_samples, b.num_samples);
    ++count[a.effect_id.empty() ? "control" : a.effect_id];
    if (a.effect_id.empty()) continue;
    EXPECT_EQ(std::string(EffectId(a.descriptor.effect->effect)), a.effect_id);
    // A solvable strength lands on its target (bisection) unless its range stops it short; it never
    // overshoots by more than the bisection's step.
    if (a.design.rfind("cic", 0) != 0) {
      EXPECT_LE(a.descriptor.strength_z, 1.02 * a.descriptor.target_z) << a.effect_id << " " << a.design;
      on_target += std::abs(a.descriptor.strength_z / a.descriptor.target_z - 1.0) < 0.02 ? 1 : 0;
      ++solvable;
    }
  }
  EXPECT_GE(2 * on_target, solvable);
  EXPECT_EQ(count["control"], 9);  // floor(20 * 0.45)
  for (const auto& id : IndependentEffectOrder(false)) EXPECT_GE(count[id], 1) << id;
}

TEST(IndependentCase, StepStrengthIsTheStepOverTheBlockAllanDeviation) {
  // White noise only: ADEV(tau) = N / sqrt(tau), so a step s at t = T/2 has block z
  // s / (sqrt 2 N / sqrt(T/2)).
  independent::Recipe base;
  base.noise.arw_rad_per_sqrt_s = 1e-3;
  independent::Recipe full = base;
  full.bias_step = independent::BiasStep{2e-4, 500.0};
  BenchmarkCase d;
  MeasureIndependentStrength(base, full, "bias_step", 100000, &d);
  EXPECT_NEAR(d.halves_z, 2e-4 / (std::sqrt(2.0) * 1e-3 / std::sqrt(500.0)), 1e-3 * d.halves_z);
  EXPECT_EQ(d.kurtosis_z, 0.0);
}

TEST(IndependentCase, SpikeStrengthMatchesTheSampleKurtosis) {
  // The kurtosis z of the expected excess kurtosis of first differences, against the excess
  // kurtosis of a long record's differences (z within a few units of its null sd).
  independent::Recipe base;
  base.noise.arw_rad_per_sqrt_s = 1e-3;
  independent::Recipe full = base;
  full.spikes = independent::Spikes{0.5, 0.05, 8.0, false};
  const std::int64_t n = 400000;
  BenchmarkCase d;
  MeasureIndependentStrength(base, full, "outliers", n, &d);
  const double z_sample = IncrementKurtosisZ(independent::Generate(full, n, 3, 0));
  EXPECT_GT(d.kurtosis_z, 20.0);
  // The sample kurtosis of heavy-tailed spikes scatters widely: agreement within a factor 2.
  EXPECT_NEAR(std::log(z_sample / d.kurtosis_z), 0.0, std::log(2.0)) << z_sample << " vs " << d.kurtosis_z;
}

// A plain rounding at an LSB of 2.4 sigma: how heavy the increments' tails are depends on where
// the bias puts the samples on the grid (on a level: heavier, +0.70; between two: lighter, -0.60;
// Sheppard's average over every place: -0.06). The strength follows the bias, and matches each
// record's sample kurtosis (n = 4e5 increments: the null sd of z is ~1; within 5 or 5 %).
TEST(IndependentCase, RoundingStrengthFollowsWhereTheBiasPutsTheGrid) {
  const double sigma = 0.01, lsb = 2.4 * sigma;  // rad/s per sample at 100 Hz
  independent::Recipe base;
  base.noise.arw_rad_per_sqrt_s = sigma / 10.0;
  const std::int64_t n = 400000;
  double z_on_level = 0.0, z_between = 0.0;
  for (double place : {0.0, 0.25, 0.5}) {
    base.noise.bias_rad_per_s = (7.0 + place) * lsb;
    independent::Recipe full = base;
    full.rate_quantizer = independent::RateQuantizer{lsb, false};
    BenchmarkCase d;
    MeasureIndependentStrength(base, full, "rate_quantization", n, &d);
    const double z_sample = std::abs(IncrementKurtosisZ(independent::Generate(full, n, 5, 0)));
    EXPECT_NEAR(d.kurtosis_z, z_sample, std::max(5.0, 0.05 * z_sample)) << "place " << place;
    if (place == 0.0) z_on_level = d.kurtosis_z;
    if (place == 0.5) z_between = d.kurtosis_z;
  }
  EXPECT_GT(z_on_level, 60.0);  // 0.70 / sqrt(24 / n) = 90
  EXPECT_GT(z_between, 60.0);   // 0.60 / sqrt(24 / n) = 77
}

}  // namespace
}  // namespace allanlab::experiments
