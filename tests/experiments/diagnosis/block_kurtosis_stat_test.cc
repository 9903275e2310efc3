// The kurtosis view's normal-deviate scale (experiments/diagnosis/block_kurtosis.h,
// KurtosisNormalDeviate) on iid Gaussian samples drawn with the standard library (not sim/):
// at the view's fewest increments, n = 255, the transformed statistic is standard normal in its
// mean, sd and upper tail, where the raw excess kurtosis, standardised by its own mean and sd, puts
// several times too many draws beyond 3.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "experiments/diagnosis/block_kurtosis.h"

namespace allanlab::experiments {
namespace {

double ExcessKurtosis(const std::vector<double>& x) {
  double mean = 0.0;
  for (double v : x) mean += v;
  mean /= static_cast<double>(x.size());
  double m2 = 0.0, m4 = 0.0;
  for (double v : x) {
    const double d = (v - mean) * (v - mean);
    m2 += d;
    m4 += d * d;
  }
  return static_cast<double>(x.size()) * m4 / (m2 * m2) - 3.0;
}

// 20000 draws: the mean's SE is 0.007 and the sd's 0.005; P(z > 3) = 0.00135 gives 27 expected
// draws beyond 3 (sd 5.2). Tolerances: 5 SE on the moments, 4 sd on the tail count. The raw
// statistic's tail (skewness 0.87) holds ~4x that count, so the same bound fails it.
TEST(BlockKurtosisStat, NormalDeviateIsStandardNormalForGaussianIncrements) {
  constexpr int kDraws = 20000;
  constexpr std::int64_t kN = 255;
  std::mt19937_64 rng(20261128);
  std::normal_distribution<double> normal;
  std::vector<double> x(kN), z(kDraws), raw(kDraws);
  for (int d = 0; d < kDraws; ++d) {
    for (double& v : x) v = normal(rng);
    raw[d] = ExcessKurtosis(x);
    z[d] = KurtosisNormalDeviate(raw[d], kN);
  }
  auto moments = [](const std::vector<double>& v, double* mean, double* sd) {
    *mean = 0.0;
    for (double e : v) *mean += e;
    *mean /= static_cast<double>(v.size());
    double ss = 0.0;
    for (double e : v) ss += (e - *mean) * (e - *mean);
    *sd = std::sqrt(ss / static_cast<double>(v.size() - 1));
  };
  double mean = 0.0, sd = 0.0;
  moments(z, &mean, &sd);
  EXPECT_NEAR(mean, 0.0, 5.0 * 1.0 / std::sqrt(kDraws));
  EXPECT_NEAR(sd, 1.0, 5.0 * 1.0 / std::sqrt(2.0 * kDraws));
  const double expected = kDraws * 0.5 * std::erfc(3.0 / std::sqrt(2.0));
  const double bound = expected + 4.0 * std::sqrt(expected);
  int beyond = 0;
  for (double e : z) beyond += e > 3.0;
  EXPECT_LE(beyond, bound);
  EXPECT_GE(beyond, expected - 4.0 * std::sqrt(expected));
  double raw_mean = 0.0, raw_sd = 0.0;
  moments(raw, &raw_mean, &raw_sd);
  int raw_beyond = 0;
  for (double e : raw) raw_beyond += (e - raw_mean) / raw_sd > 3.0;
  EXPECT_GT(raw_beyond, bound) << "the raw statistic's tail should be what the transform mends";
}

TEST(BlockKurtosisStat, NormalDeviateIsNaNWhereUndefined) {
  EXPECT_TRUE(std::isnan(KurtosisNormalDeviate(std::nan(""), 300)));
  EXPECT_TRUE(std::isnan(KurtosisNormalDeviate(0.0, 5)));
}

}  // namespace
}  // namespace allanlab::experiments
