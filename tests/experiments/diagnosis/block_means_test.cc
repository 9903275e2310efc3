// The block-mean covariance (docs/theory.md §6.7, eq. 6.7.3) against closed forms derived here
// from the processes' definitions, not from the code's sum over the autocovariance:
//   white rate noise of variance s^2 per sample: block means independent with variance s^2 / m, so
//     the differences are MA(1): c = (2, -1, 0, ...) s^2 / m;
//   rate random walk K (continuous): Var(u_{b+k} - u_b) = K^2 T (k - 1/3), T = m tau0, so
//     c = (2/3, 1/6, 0, ...) K^2 T (sim/'s point-sampled walk differs by O(1/m)).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "experiments/diagnosis/block_means.h"

namespace allanlab::experiments {
namespace {

TEST(BlockMeans, WhiteNoiseDifferencesAreMovingAverage) {
  sim::SensorModel model;
  model.sample_rate_hz = 100.0;
  sim::WhiteRateNoise white;
  white.arw_rad_per_sqrt_s = 1e-3;
  model.terms = {white};
  const std::int64_t m = 500;
  const double s2 = 1e-6 * model.sample_rate_hz;  // N^2 / tau0
  const std::vector<double> c = BlockDifferenceCovariance(model, m, 16);
  ASSERT_EQ(c.size(), 15u);
  EXPECT_NEAR(c[0], 2.0 * s2 / m, 1e-9 * s2 / m);
  EXPECT_NEAR(c[1], -s2 / m, 1e-9 * s2 / m);
  for (std::size_t k = 2; k < c.size(); ++k) EXPECT_NEAR(c[k], 0.0, 1e-9 * s2 / m) << k;
}

TEST(BlockMeans, RandomWalkDifferences) {
  sim::SensorModel model;
  model.sample_rate_hz = 100.0;
  sim::RandomWalkRate walk;
  walk.rrw_rad_per_s_per_sqrt_s = 1e-5;
  model.terms = {walk};
  const std::int64_t m = 2000;
  const double k2t = 1e-10 * static_cast<double>(m) / model.sample_rate_hz;
  const std::vector<double> c = BlockDifferenceCovariance(model, m, 32);
  EXPECT_NEAR(c[0], 2.0 / 3.0 * k2t, 2e-3 * k2t);
  EXPECT_NEAR(c[1], 1.0 / 6.0 * k2t, 2e-3 * k2t);
  for (std::size_t k = 2; k < c.size(); ++k) EXPECT_NEAR(c[k], 0.0, 1e-6 * k2t) << k;
}

// A rate ramp of unknown sign is a random slope of variance R^2: every difference shares it.
TEST(BlockMeans, RampAddsAConstant) {
  sim::SensorModel model;
  model.sample_rate_hz = 10.0;
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

}  // namespace
}  // namespace allanlab::experiments
