// The kurtosis view's statistic computed for every octave at once (block sums paired up from one
// octave to the next, experiments/diagnosis/block_kurtosis.h) against the definition computed
// directly for each m (block means summed sample by sample, long double moments), on Gaussian,
// heavy-tailed and two-level records; a view that is off by one block or pairs the wrong sums
// fails here.
#include "experiments/diagnosis/block_kurtosis.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace allanlab::experiments {
namespace {

double DirectKurtosis(const std::vector<double>& x, std::int64_t m) {
  const std::size_t blocks = x.size() / static_cast<std::size_t>(m);
  std::vector<long double> means(blocks);
  for (std::size_t b = 0; b < blocks; ++b) {
    long double s = 0.0L;
    for (std::int64_t k = 0; k < m; ++k) s += x[b * static_cast<std::size_t>(m) + static_cast<std::size_t>(k)];
    means[b] = s / m;
  }
  const std::size_t n = blocks - 1;
  long double mean = 0.0L;
  for (std::size_t i = 0; i < n; ++i) mean += means[i + 1] - means[i];
  mean /= n;
  long double m2 = 0.0L, m4 = 0.0L;
  for (std::size_t i = 0; i < n; ++i) {
    const long double d = means[i + 1] - means[i] - mean;
    m2 += d * d;
    m4 += d * d * d * d;
  }
  return static_cast<double>(n * m4 / (m2 * m2) - 3.0L);
}

TEST(BlockKurtosis, MatchesTheDefinitionAtEveryOctave) {
  std::mt19937_64 rng(17);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::bernoulli_distribution spike(0.001), flip(0.002);
  const std::size_t n = 100003;  // not a multiple of any block: trailing partial blocks dropped
  std::vector<double> gaussian(n), spiky(n), telegraph(n);
  double level = 1.0, walk = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    walk += 0.01 * normal(rng);
    gaussian[k] = 3.0 + normal(rng) + walk;  // an offset and a random walk: increments still Gaussian
    spiky[k] = normal(rng) + (spike(rng) ? 40.0 : 0.0);
    if (flip(rng)) level = -level;
    telegraph[k] = level + 0.05 * normal(rng);
  }
  const std::vector<std::int64_t> octaves = {1, 2, 4, 8, 16, 32, 64, 128, 256};
  const std::vector<std::int64_t> mixed = {3, 6, 12, 100, 200};  // from scratch where m does not double
  for (const auto* x : {&gaussian, &spiky, &telegraph}) {
    for (const auto* ms : {&octaves, &mixed}) {
      const std::vector<double> fast = BlockIncrementKurtosis(*x, *ms);
      ASSERT_EQ(fast.size(), ms->size());
      for (std::size_t i = 0; i < ms->size(); ++i) {
        const double direct = DirectKurtosis(*x, (*ms)[i]);
        EXPECT_NEAR(fast[i], direct, 1e-9 * (1.0 + std::abs(direct))) << "m=" << (*ms)[i];
      }
    }
  }
  // What the view is for: spikes lift it, Gaussian increments sit near 0 (at m = 1, 1e5
  // increments: sd ~ sqrt(24 / 1e5) = 0.015).
  EXPECT_NEAR(BlockIncrementKurtosis(gaussian, octaves)[0], 0.0, 0.1);
  EXPECT_GT(BlockIncrementKurtosis(spiky, octaves)[0], 5.0);
}

TEST(BlockKurtosis, ConstantIncrementsGiveNaN) {
  std::vector<double> ramp(4096);
  for (std::size_t k = 0; k < ramp.size(); ++k) ramp[k] = 0.5 * static_cast<double>(k % 2);
  const std::vector<std::int64_t> ms = {2, 4};
  for (double v : BlockIncrementKurtosis(ramp, ms)) EXPECT_TRUE(std::isnan(v));
}

}  // namespace
}  // namespace allanlab::experiments
