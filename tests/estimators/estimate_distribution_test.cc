// The weighted chi-square distribution (Imhof's inversion) against closed forms and an independent
// Monte Carlo, and the weights of an Allan estimate against what they must satisfy.
#include "estimators/estimate_distribution.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <boost/math/distributions/chi_squared.hpp>
#include <gtest/gtest.h>

#include "estimators/exact_quadratic_moments.h"

namespace allanlab::estimators {
namespace {

// k equal weights 1/k: Q = chi-square(k) / k exactly.
TEST(WeightedChiSquare, EqualWeightsAreAScaledChiSquare) {
  for (int k : {1, 2, 5, 20, 80}) {
    const std::vector<double> w(static_cast<std::size_t>(k), 1.0 / k);
    const boost::math::chi_squared chi2(k);
    for (double x : {0.05, 0.3, 0.8, 1.0, 1.7, 3.0}) {
      EXPECT_NEAR(WeightedChiSquareCdf(w, x), boost::math::cdf(chi2, k * x), 2e-7)
          << "k=" << k << " x=" << x;
    }
    for (double p : {0.025, 0.1585, 0.8415, 0.975}) {
      EXPECT_NEAR(WeightedChiSquareQuantile(w, p), boost::math::quantile(chi2, p) / k,
                  1e-6 * boost::math::quantile(chi2, p) / k + 1e-9)
          << "k=" << k << " p=" << p;
    }
  }
}

// Weights (1/2, 1/2): Q = chi-square(2) / 2, an exponential of mean 1, CDF 1 - exp(-x).
TEST(WeightedChiSquare, PairIsExponential) {
  const std::vector<double> w = {0.5, 0.5};
  for (double x : {0.1, 0.5, 1.0, 2.5}) EXPECT_NEAR(WeightedChiSquareCdf(w, x), 1.0 - std::exp(-x), 2e-7);
}

// Unequal weights against 400000 independent draws (standard-library chi-square): the CDF's
// binomial error there is <= 0.0008; 5 of those.
TEST(WeightedChiSquare, UnequalWeightsMatchMonteCarlo) {
  const std::vector<double> w = {0.4, 0.25, 0.15, 0.1, 0.06, 0.04};
  std::mt19937_64 rng(7);
  std::chi_squared_distribution<double> one(1.0);
  const int draws = 400000;
  const std::vector<double> xs = {0.2, 0.5, 1.0, 1.5, 2.5};
  std::vector<int> below(xs.size(), 0);
  for (int i = 0; i < draws; ++i) {
    double q = 0.0;
    for (double v : w) q += v * one(rng);
    for (std::size_t k = 0; k < xs.size(); ++k) below[k] += q <= xs[k];
  }
  for (std::size_t k = 0; k < xs.size(); ++k) {
    const double mc = static_cast<double>(below[k]) / draws;
    EXPECT_NEAR(WeightedChiSquareCdf(w, xs[k]), mc, 5.0 * std::sqrt(mc * (1 - mc) / draws) + 1e-6)
        << "x=" << xs[k];
  }
}

// The weights sum to 1 and their EDF, 1 / sum w^2, is the exact EDF of the same reduced record
// (exact_edf.h, which takes the moments from the filter's autocovariance directly, not from
// eigenvalues); for m <= m' they are the record's own.
TEST(EstimateWeights, SumToOneAndCarryTheExactEdf) {
  for (Statistic s : {Statistic::kAllanOverlapping, Statistic::kAllanNonOverlapping,
                      Statistic::kHadamardOverlapping, Statistic::kModifiedAllan}) {
    for (int alpha : {0, -1, -2, 2}) {
      const std::int64_t m = 8, n = 96;
      const std::vector<double> w = EstimateWeights(s, alpha, m, n);
      ASSERT_FALSE(w.empty()) << static_cast<int>(s) << " alpha " << alpha;
      double sum = 0.0, squares = 0.0;
      for (double v : w) {
        EXPECT_GE(v, 0.0);
        sum += v;
        squares += v * v;
      }
      EXPECT_NEAR(sum, 1.0, 1e-12);
      // Generalised autocovariances written out: white delta, random walk -j/2.
      if (alpha != 0 && alpha != -2) continue;
      const std::vector<double> filter = DifferenceFilter(s, m);
      const std::int64_t count = TermCount(s, m, n);
      const std::int64_t stride =
          s == Statistic::kAllanNonOverlapping || s == Statistic::kHadamardNonOverlapping ? m : 1;
      std::vector<double> r(static_cast<std::size_t>((count - 1) * stride + filter.size() + 1), 0.0);
      for (std::size_t j = 0; j < r.size(); ++j) r[j] = alpha == 0 ? (j == 0 ? 1.0 : 0.0) : -0.5 * j;
      const AvarMoments moments = ExactQuadraticMoments(r, filter, count, stride);
      EXPECT_NEAR(1.0 / squares, 2.0 * moments.mean * moments.mean / moments.variance,
                  1e-9 / squares)
          << static_cast<int>(s) << " alpha " << alpha;
    }
  }
}

// The lumped weights EstimateQuantilesAt uses against the full set, at 16 clusters (225 weights).
TEST(EstimateWeights, LumpedQuantilesMatchTheFullSet) {
  for (int alpha : {0, -1, -2}) {
    const std::vector<double> w = EstimateWeights(Statistic::kAllanOverlapping, alpha, 256, 4096);
    ASSERT_GT(w.size(), 200u);
    const EstimateQuantiles q = EstimateQuantilesAt(Statistic::kAllanOverlapping, alpha, 256, 4096, 0.95);
    ASSERT_TRUE(q.ok);
    EXPECT_NEAR(q.low / WeightedChiSquareQuantile(w, 0.025), 1.0, 1e-3) << alpha;
    EXPECT_NEAR(q.high / WeightedChiSquareQuantile(w, 0.975), 1.0, 1e-3) << alpha;
  }
}

TEST(EstimateWeights, EmptyWhereNotCovered) {
  EXPECT_TRUE(EstimateWeights(Statistic::kTotal, 0, 8, 96).empty());
  EXPECT_TRUE(EstimateWeights(Statistic::kAllanOverlapping, 3, 8, 96).empty());
  EXPECT_TRUE(EstimateWeights(Statistic::kAllanOverlapping, 0, 60, 96).empty());  // m > N/2
  EXPECT_TRUE(EstimateWeights(Statistic::kAllanOverlapping, 2, 64, 1024).empty());  // phase, reduced
}

// The reduced scale: at 8 clusters the quantiles for m = 512 (computed at m' = 16) and for m = 16
// itself agree, and the white-noise quantiles match the 2.5 % / 97.5 % points of 20000 simulated
// OAVAR estimates on 4096 samples at m = 512 (standard-library normals; the empirical quantile's
// error there is ~0.008 and ~0.02).
TEST(EstimateWeights, ReducedScaleMatchesSimulatedQuantiles) {
  const EstimateQuantiles reduced = EstimateQuantilesAt(Statistic::kAllanOverlapping, 0, 512, 4096, 0.95);
  const EstimateQuantiles direct = EstimateQuantilesAt(Statistic::kAllanOverlapping, 0, 16, 128, 0.95);
  ASSERT_TRUE(reduced.ok && direct.ok);
  EXPECT_NEAR(reduced.low, direct.low, 1e-12);
  EXPECT_NEAR(reduced.high, direct.high, 1e-12);

  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal;
  const std::int64_t n = 4096, m = 512;
  std::vector<double> estimates;
  std::vector<double> phase(n + 1);
  for (int trial = 0; trial < 20000; ++trial) {
    phase[0] = 0.0;
    for (std::int64_t i = 0; i < n; ++i) phase[i + 1] = phase[i] + normal(rng);
    double sum = 0.0;
    for (std::int64_t t = 0; t + 2 * m <= n; ++t) {
      const double d = phase[t + 2 * m] - 2.0 * phase[t + m] + phase[t];
      sum += d * d;
    }
    // E[OAVAR] = 1 / m for unit white rate noise: the ratio to it.
    estimates.push_back(sum / (2.0 * m * m * static_cast<double>(n - 2 * m + 1)) * m);
  }
  std::sort(estimates.begin(), estimates.end());
  EXPECT_NEAR(estimates[500], reduced.low, 0.02);
  EXPECT_NEAR(estimates[19500], reduced.high, 0.05);
  // chi-square(EDF) would put the 2.5 % point at 0.32 here (EDF 9.7): far outside that band.
  EXPECT_GT(reduced.low, 0.35);
}

}  // namespace
}  // namespace allanlab::estimators
