// The block-mean covariance (docs/theory.md §6.7, eq. 6.7.3) against closed forms derived here
// from the processes' definitions, not from the code's sum over the autocovariance:
//   white rate noise of variance s^2 per sample: block means independent with variance s^2 / m, so
//     the differences are MA(1): c = (2, -1, 0, ...) s^2 / m;
//   rate random walk K (continuous): Var(u_{b+k} - u_b) = K^2 T (k - 1/3), T = m tau0, so
//     c = (2/3, 1/6, 0, ...) K^2 T (sim/'s point-sampled walk differs by O(1/m)).
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <vector>

#include "experiments/diagnosis/block_means.h"
#include "experiments/diagnosis/diagnose.h"
#include "independent/recipe.h"
#include "tests/support/diagnosis_record.h"

namespace allanlab::experiments {
namespace {

// At 100 Hz: white rate noise of N = 1e-3 rad/sqrt(s), and a rate random walk of K = 1e-5 rad/s/sqrt(s).
sim::SensorModel WhiteModel() {
  sim::SensorModel model;
  model.sample_clock = SampleClock::FromRateHz(100.0);
  model.terms = {sim::WhiteRateNoise{.arw_rad_per_sqrt_s = 1e-3}};
  return model;
}

sim::SensorModel WalkModel() {
  sim::SensorModel model;
  model.sample_clock = SampleClock::FromRateHz(100.0);
  model.terms = {sim::RandomWalkRate{.rrw_rad_per_s_per_sqrt_s = 1e-5}};
  return model;
}

TEST(BlockMeans, WhiteNoiseDifferencesAreMovingAverage) {
  const sim::SensorModel model = WhiteModel();
  const std::int64_t m = 500;
  const double s2 = 1e-6 * model.sample_clock.rate_hz();  // N^2 / tau0
  const std::vector<double> c = BlockDifferenceCovariance(model, m, 16);
  ASSERT_EQ(c.size(), 15u);
  EXPECT_NEAR(c[0], 2.0 * s2 / m, 1e-9 * s2 / m);
  EXPECT_NEAR(c[1], -s2 / m, 1e-9 * s2 / m);
  for (std::size_t k = 2; k < c.size(); ++k) EXPECT_NEAR(c[k], 0.0, 1e-9 * s2 / m) << k;
}

TEST(BlockMeans, RandomWalkDifferences) {
  const sim::SensorModel model = WalkModel();
  const std::int64_t m = 2000;
  const double k2t = 1e-10 * static_cast<double>(m) / model.sample_clock.rate_hz();
  const std::vector<double> c = BlockDifferenceCovariance(model, m, 32);
  EXPECT_NEAR(c[0], 2.0 / 3.0 * k2t, 2e-3 * k2t);
  EXPECT_NEAR(c[1], 1.0 / 6.0 * k2t, 2e-3 * k2t);
  for (std::size_t k = 2; k < c.size(); ++k) EXPECT_NEAR(c[k], 0.0, 1e-6 * k2t) << k;
}

// A block mean's spread about the mean of all B blocks (the block-mean panel's band):
//   white: block means independent, Var(u_b - mean u) = (s^2 / m) (1 - 1/B);
//   continuous random walk: D(k) = K^2 T (k - 1/3) for k >= 1, so with
//     Var(u_b - mean u) = (1/B) sum_j D(|b - j|) - (1/(2 B^2)) sum_{i,j} D(|i - j|),
//     sum_{j != b} |b - j| = b (b + 1) / 2 + (B - 1 - b) (B - b) / 2 and sum_{i != j} |i - j| = (B^3 - B) / 3:
//     largest at the ends, where the walk strays furthest from its mean.
TEST(BlockMeans, DeviationFromTheMeanOfAllBlocks) {
  const sim::SensorModel white_model = WhiteModel();
  const std::int64_t m = 500;
  const double s2 = 1e-6 * white_model.sample_clock.rate_hz();
  const std::vector<double> sd_white = BlockMeanDeviationSd(white_model, m, 16);
  ASSERT_EQ(sd_white.size(), 16u);
  for (double sd : sd_white) EXPECT_NEAR(sd * sd, s2 / m * (1.0 - 1.0 / 16.0), 1e-9 * s2 / m);

  const sim::SensorModel walk_model = WalkModel();
  const int blocks = 32;
  const std::int64_t mw = 2000;
  const double k2t = 1e-10 * static_cast<double>(mw) / walk_model.sample_clock.rate_hz();
  const std::vector<double> sd_walk = BlockMeanDeviationSd(walk_model, mw, blocks);
  const double big_b = blocks;
  const double all = k2t * ((big_b * big_b * big_b - big_b) / 3.0 - big_b * (big_b - 1.0) / 3.0);
  for (int b : {0, 5, 16, blocks - 1}) {
    const double row = k2t * (b * (b + 1) / 2.0 + (blocks - 1.0 - b) * (blocks - b) / 2.0 - (blocks - 1.0) / 3.0);
    const double expected = row / big_b - all / (2.0 * big_b * big_b);
    EXPECT_NEAR(sd_walk[b] * sd_walk[b], expected, 2e-3 * expected) << b;
  }
  EXPECT_GT(sd_walk.front(), 1.5 * sd_walk[blocks / 2]);
}

// A rate ramp of unknown sign is a random slope of variance R^2: every difference shares it.
TEST(BlockMeans, RampAddsAConstant) {
  sim::SensorModel model;
  model.sample_clock = SampleClock::FromRateHz(10.0);
  sim::WhiteRateNoise white;
  white.arw_rad_per_sqrt_s = 1e-3;
  sim::RateRamp ramp;
  ramp.ramp_rad_per_s2 = 1e-7;
  model.terms = {white};
  const std::vector<double> plain = BlockDifferenceCovariance(model, 100, 16);
  model.terms.push_back(ramp);
  const std::vector<double> with_ramp = BlockDifferenceCovariance(model, 100, 16);
  const double block_s = 10.0;
  for (std::size_t k = 0; k < plain.size(); ++k) {
    EXPECT_NEAR(with_ramp[k] - plain[k], 1e-14 * block_s * block_s, 1e-9 * 1e-14 * block_s * block_s);
  }
}

// Means of blocks of 0, 1, 2, ...: block b of m samples averages b m + (m - 1) / 2; the last
// n mod blocks samples are left out.
TEST(BlockMeans, MeansOfEqualBlocksLeaveTheRemainderOut) {
  std::vector<double> x(103);
  std::iota(x.begin(), x.end(), 0.0);
  const std::vector<double> means = BlockMeans(x, 10);
  ASSERT_EQ(means.size(), 10u);
  for (int b = 0; b < 10; ++b) EXPECT_DOUBLE_EQ(means[b], b * 10 + 4.5) << b;
}

TEST(BlockMeans, DeterministicPathIsTheStepAloneAndEmptyWithoutEvents) {
  sim::SensorModel model;
  model.sample_clock = SampleClock::FromRateHz(10.0);
  model.terms = {sim::WhiteRateNoise{}};
  EXPECT_TRUE(DeterministicPath(model, 100).empty());
  model.terms.push_back(sim::BiasStep{2e-4, 4.0});
  const std::vector<double> path = DeterministicPath(model, 100);
  ASSERT_EQ(path.size(), 100u);
  for (int k = 0; k < 100; ++k) EXPECT_EQ(path[k], k >= 40 ? 2e-4 : 0.0) << k;
}

// The series a plot of the block-mean views draws, on an independent record with a step of
// 6e-5 rad/s at 98.3 s (16384 samples at 100 Hz): 64 blocks of 256 samples, the record's means as
// BlockMeans gives them, no path for the white-noise baseline, and the verdict's path a step of
// its fitted size at its fitted time.
TEST(BlockMeans, TheDiagnosisKeepsTheRecordsBlockMeansAndTheVerdictsPath) {
  independent::Recipe recipe;
  recipe.rate_hz = 100.0;
  recipe.noise.arw_rad_per_sqrt_s = 1e-5;
  recipe.bias_step = independent::BiasStep{6e-5, 98.3};
  const std::vector<double> record = independent::Generate(recipe, 16384, 3, 0);
  DiagnosisSummary s;
  ASSERT_TRUE(DiagnoseRecord(testing::TestDiagnoseOptions({estimators::Coefficient::kN}), record, SampleClock::FromPeriodS(0.01), &s))
      << s.message;
  ASSERT_EQ(s.verdict, "bias_step") << testing::DescribeVerdict(s);
  const BlockMeanSeries& b = s.block_means;
  ASSERT_EQ(b.record.size(), 64u);
  EXPECT_DOUBLE_EQ(b.block_s, 2.56);
  EXPECT_DOUBLE_EQ(b.time_s.front(), 1.28);
  EXPECT_EQ(b.record, BlockMeans(record, 64));
  EXPECT_EQ(b.baseline_path, std::vector<double>(64, 0.0));
  ASSERT_EQ(b.verdict_path.size(), 64u);
  const EffectInstance& step = s.candidates[s.verdict_candidate].effects[0];
  const double size = step.params.at("size_rad_per_s"), at = step.params.at("time_s");
  for (std::size_t i = 0; i < 64; ++i) {
    const double start = static_cast<double>(i) * b.block_s, end = start + b.block_s;
    if (end <= at) {
      EXPECT_EQ(b.verdict_path[i], 0.0) << i;
    } else if (start >= at + 0.01) {
      EXPECT_NEAR(b.verdict_path[i], size, 1e-12 * std::abs(size)) << i;
    }
  }
}

}  // namespace
}  // namespace allanlab::experiments
