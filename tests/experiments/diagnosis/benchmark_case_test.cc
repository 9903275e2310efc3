// The blind benchmark's draw (benchmark_case.h) and scoring (benchmark_score.h): deterministic
// draws, the strength scale (zero for a control, monotone in the effect's size, the solve hitting
// its target), and the scores on hand-made outcomes. Short records keep it to seconds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "experiments/diagnosis/benchmark_case.h"
#include "experiments/diagnosis/benchmark_score.h"
#include "sim/sensor_spec.h"

namespace allanlab::experiments {
namespace {

BenchmarkDrawOptions Small() {
  BenchmarkDrawOptions o;
  o.min_duration_s = 60.0;
  o.max_duration_s = 120.0;
  o.max_samples = 20000;
  return o;
}

TEST(BenchmarkCaseTest, DrawsAreDeterministicAndInRange) {
  const BenchmarkDrawOptions o = Small();
  for (int i = 0; i < 6; ++i) {
    BenchmarkCase a, b;
    std::string why;
    ASSERT_TRUE(DrawBenchmarkCase(o, 11, i, &a, &why)) << why;
    ASSERT_TRUE(DrawBenchmarkCase(o, 11, i, &b, &why)) << why;
    EXPECT_EQ(a.preset, b.preset);
    EXPECT_EQ(a.num_samples, b.num_samples);
    EXPECT_EQ(a.sample_clock, b.sample_clock);
    EXPECT_EQ(a.strength_z, b.strength_z);
    EXPECT_EQ(a.effect.has_value(), b.effect.has_value());
    if (a.effect) {
      EXPECT_EQ(a.effect->params, b.effect->params);
    }
    EXPECT_LE(a.num_samples, o.max_samples);
    EXPECT_GE(a.sample_clock.rate_hz(), o.min_rate_hz * (1 - 1e-12));
    EXPECT_LE(a.sample_clock.rate_hz(), o.max_rate_hz);
    EXPECT_GE(a.duration_s(), o.min_duration_s - a.sample_clock.period_s());
    EXPECT_LE(a.duration_s(), o.max_duration_s + a.sample_clock.period_s());
    EXPECT_FALSE(a.base.band_limit.enabled());
    EXPECT_FALSE(a.base.rate_quantizer.has_value());
  }
}

TEST(BenchmarkCaseTest, ControlHasNoStrengthAndEffectsGrowWithSize) {
  sim::SensorModel base;
  std::string why;
  ASSERT_TRUE(sim::LoadPreset("tg100", &base, &why)) << why;
  base.band_limit = {};
  base.sample_clock = SampleClock::FromRateHz(200.0);
  BenchmarkCase c;
  ASSERT_TRUE(MeasureStrength(base, std::nullopt, 20000, &c, &why)) << why;
  EXPECT_LT(c.strength_z, 1e-6);  // the baseline fit absorbs the baseline exactly
  double previous = 0.0;
  for (double sigma : {1e-6, 1e-5, 1e-4}) {
    EffectInstance gm{Effect::kGaussMarkov, {{"sigma_rad_per_s", sigma}, {"correlation_time_s", 1.0}}};
    ASSERT_TRUE(MeasureStrength(base, gm, 20000, &c, &why)) << why;
    EXPECT_GT(c.strength_z, previous) << sigma;
    previous = c.strength_z;
    EXPECT_GT(c.peak_tau_s, 0.05);
    EXPECT_LT(c.peak_tau_s, 20.0);
  }
  EXPECT_GT(previous, 5.0);  // well beyond the Bonferroni level (~3.5)
  const auto [lo, hi] = c.ExpectedTauRange(3.5);
  EXPECT_LE(lo, c.peak_tau_s);
  EXPECT_GE(hi, c.peak_tau_s);
}

TEST(BenchmarkCaseTest, TheStrengthSolveHitsItsTarget) {
  BenchmarkDrawOptions o = Small();
  o.control_fraction = 0.0;
  int solved = 0;
  for (int i = 0; i < 8; ++i) {
    BenchmarkCase c;
    std::string why;
    ASSERT_TRUE(DrawBenchmarkCase(o, 5, i, &c, &why)) << why;
    ASSERT_TRUE(c.effect.has_value());
    EXPECT_EQ(c.strength_class, StrengthClass(false, c.strength_z));
    // Bisection in 16 halvings of the log range: within a few per cent when reachable.
    if (std::abs(c.strength_z / c.target_z - 1.0) < 0.05) ++solved;
  }
  EXPECT_GE(solved, 4);
}

BenchmarkCase GaussMarkovCase() {
  BenchmarkCase c;
  c.index = 3;
  c.preset = "tg100";
  c.sample_clock = SampleClock::FromRateHz(100.0);
  c.num_samples = 10000;
  c.effect = EffectInstance{Effect::kGaussMarkov, {{"sigma_rad_per_s", 1e-4}, {"correlation_time_s", 2.0}}};
  c.strength_z = 20.0;
  c.strength_class = "clear";
  c.tau_s = {0.1, 1.0, 10.0};
  c.gap_z = {1.0, 20.0, 5.0};
  c.peak_tau_s = 1.0;
  return c;
}

TEST(BenchmarkScoreTest, RightEffectLocalizationAndShrink) {
  BenchmarkOutcome o;
  o.ok = true;
  o.significant = true;
  o.threshold_z = 3.5;
  o.verdict = "random_telegraph";
  o.also_consistent = {"gauss_markov"};
  o.regions = {{"oavar", 0.8, 12.0}};
  o.has_heldout = true;
  o.heldout_before_chi2 = 400.0;
  o.heldout_after_chi2 = 40.0;
  BenchmarkRow r = ScoreBenchmarkCase(GaussMarkovCase(), o);
  EXPECT_TRUE(r.detected);
  EXPECT_TRUE(r.right);  // named as also consistent
  EXPECT_EQ(r.expected_tau_min_s, 1.0);
  EXPECT_EQ(r.expected_tau_max_s, 10.0);
  EXPECT_EQ(r.overlap, 1);
  EXPECT_EQ(r.contain, 1);
  EXPECT_DOUBLE_EQ(r.shrink, 10.0);
  // 40 on 10 points is far above chi2_10's 95 % quantile (18.31); 18 on 10 points is within it.
  EXPECT_FALSE(r.heldout_at_model_level);
  o.heldout_points = 10;
  o.heldout_before_chi2 = 60.0;
  o.heldout_after_chi2 = 18.0;
  r = ScoreBenchmarkCase(GaussMarkovCase(), o);
  EXPECT_TRUE(r.heldout_at_model_level);
  o.heldout_after_chi2 = 18.5;
  EXPECT_FALSE(ScoreBenchmarkCase(GaussMarkovCase(), o).heldout_at_model_level);
  o.regions = {{"psd", 20.0, 50.0}};
  o.verdict = "harmonic";
  o.also_consistent.clear();
  r = ScoreBenchmarkCase(GaussMarkovCase(), o);
  EXPECT_FALSE(r.right);
  EXPECT_EQ(r.overlap, 0);
  EXPECT_EQ(r.shrink, 0.0);  // only right diagnoses count
  EXPECT_EQ(VerdictColumn(o), "harmonic");
  o.verdict = "bias_step+outliers";
  EXPECT_EQ(VerdictColumn(o), "pair");
}

TEST(BenchmarkScoreTest, SummaryCountsAndWilsonIntervals) {
  const Proportion none = MakeProportion(0, 20);
  EXPECT_EQ(none.low, 0.0);
  EXPECT_NEAR(none.high, 0.1611, 1e-3);
  const Proportion half = MakeProportion(10, 20);
  EXPECT_NEAR(half.low, 0.2993, 1e-3);
  EXPECT_NEAR(half.high, 0.7007, 1e-3);

  std::vector<BenchmarkRow> rows;
  BenchmarkCase control;
  control.strength_class = "control";
  BenchmarkOutcome clean;
  clean.ok = true;
  clean.verdict = "none";
  BenchmarkOutcome alarm = clean;
  alarm.significant = true;
  alarm.verdict = "unexplained";
  for (int i = 0; i < 19; ++i) rows.push_back(ScoreBenchmarkCase(control, clean));
  rows.push_back(ScoreBenchmarkCase(control, alarm));
  BenchmarkOutcome named = clean;
  named.significant = true;
  named.verdict = "gauss_markov";
  rows.push_back(ScoreBenchmarkCase(GaussMarkovCase(), named));
  const BenchmarkSummary s = SummarizeBenchmark(rows);
  EXPECT_EQ(s.false_alarm.successes, 1);
  EXPECT_EQ(s.false_alarm.trials, 20);
  EXPECT_EQ(s.clear_right.successes, 1);
  EXPECT_EQ(s.clear_right.trials, 1);
  EXPECT_EQ(s.confusion[0][0], 19);
  EXPECT_EQ(s.confusion[0][s.verdicts.size() - 2], 1);  // unexplained
  // Only the effects drawn get a row and a rate; the others are listed as not drawn.
  EXPECT_EQ(s.truths, (std::vector<std::string>{"control", "gauss_markov"}));
  ASSERT_EQ(s.clear_right_by_effect.size(), 1u);
  EXPECT_EQ(s.clear_right_by_effect[0].first, "gauss_markov");
  EXPECT_EQ(s.not_drawn.size(), std::size(kAllEffects) - 1);
  EXPECT_NE(std::find(s.not_drawn.begin(), s.not_drawn.end(), "resonance"), s.not_drawn.end());
  int bin_total = 0;
  for (const StrengthBin& b : s.bins) bin_total += b.detected.trials;
  EXPECT_EQ(bin_total, 1);
}

}  // namespace
}  // namespace allanlab::experiments
