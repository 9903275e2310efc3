// Chi-square intervals and the EDF dispatch per statistic (confidence.h).
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "estimators/confidence.h"

namespace allanlab::estimators {
namespace {

// chi2 with 2 degrees of freedom has F(x) = 1 - exp(-x/2): quantile(p) = -2
// ln(1 - p), so the interval [2v / q(1-p), 2v / q(p)] is [v / -ln p, v / -ln(1
// - p)] in closed form.
TEST(ChiSquareInterval, TwoDegreesOfFreedomClosedForm) {
  for (double confidence : {0.683, 0.9, 0.95}) {
    const double p = 0.5 * (1.0 - confidence);
    const Interval i = ChiSquareInterval(3.0, 2.0, confidence);
    EXPECT_NEAR(i.low, 3.0 / -std::log(p), 1e-12);
    EXPECT_NEAR(i.high, 3.0 / -std::log1p(-p), 1e-9);
  }
}

// For large edf, v edf / chi2 is about v (1 -+ z sqrt(2 / edf)); z = 1.96 at 95
// %.
TEST(ChiSquareInterval, LargeEdfApproachesNormal) {
  const double edf = 1e6;
  const Interval i = ChiSquareInterval(1.0, edf, 0.95);
  const double half_width = 1.959964 * std::sqrt(2.0 / edf);
  EXPECT_NEAR(i.low, 1.0 - half_width, 1e-5);
  EXPECT_NEAR(i.high, 1.0 + half_width, 1e-5);
}

TEST(ChiSquareInterval, ContainsTheEstimateAndWidensWithConfidence) {
  const Interval narrow = ChiSquareInterval(2.0, 7.5, 0.683);  // non-integer edf is fine
  const Interval wide = ChiSquareInterval(2.0, 7.5, 0.95);
  EXPECT_LT(narrow.low, 2.0);
  EXPECT_GT(narrow.high, 2.0);
  EXPECT_LT(wide.low, narrow.low);
  EXPECT_GT(wide.high, narrow.high);
}

TEST(ChiSquareInterval, NoDegreesOfFreedomMeansNoInformation) {
  for (double edf : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN()}) {
    const Interval i = ChiSquareInterval(2.0, edf, 0.683);
    EXPECT_EQ(i.low, 0.0);
    EXPECT_TRUE(std::isinf(i.high));
  }
}

TEST(SimpleEdf, ClustersMinusOne) {
  EXPECT_EQ(SimpleEdf(10), 9.0);
  EXPECT_EQ(SimpleEdf(2), 1.0);
  EXPECT_EQ(SimpleEdf(1), 0.0);
  EXPECT_EQ(SimpleEdf(0), 0.0);
}

// NIST SP 1065 Table 7: edf = b T/tau - c.
TEST(TotalVarianceEdf, Sp1065Table7) {
  EXPECT_DOUBLE_EQ(TotalVarianceEdf(0, 1000.0, 10.0), 150.0);
  EXPECT_DOUBLE_EQ(TotalVarianceEdf(-1, 1000.0, 10.0), 117.0 - 0.22);
  EXPECT_DOUBLE_EQ(TotalVarianceEdf(-2, 1000.0, 10.0), 93.0 - 0.36);
  EXPECT_EQ(TotalVarianceEdf(1, 1000.0, 10.0),
            0.0);  // the table has no phase-noise rows
  EXPECT_EQ(TotalVarianceEdf(-3, 1000.0, 10.0), 0.0);
}

// Greenhall & Riley count phase points, one more than rate samples.
TEST(StatisticEdf, DispatchesByStatistic) {
  const std::int64_t n = 1000, m = 10;
  EXPECT_EQ(StatisticEdf(Statistic::kAllanOverlapping, -1, m, n, 0.01),
            GreenhallRileyEdf(-1, 2, m, n + 1, true, false));
  EXPECT_EQ(StatisticEdf(Statistic::kAllanNonOverlapping, -1, m, n, 0.01),
            GreenhallRileyEdf(-1, 2, m, n + 1, false, false));
  EXPECT_EQ(StatisticEdf(Statistic::kModifiedAllan, 0, m, n, 0.01),
            GreenhallRileyEdf(0, 2, m, n + 1, true, true));
  EXPECT_EQ(StatisticEdf(Statistic::kTime, 0, m, n, 0.01),
            StatisticEdf(Statistic::kModifiedAllan, 0, m, n, 0.01));
  EXPECT_EQ(StatisticEdf(Statistic::kHadamardOverlapping, -2, m, n, 0.01),
            GreenhallRileyEdf(-2, 3, m, n + 1, true, false));
  EXPECT_EQ(StatisticEdf(Statistic::kHadamardNonOverlapping, -2, m, n, 0.01),
            GreenhallRileyEdf(-2, 3, m, n + 1, false, false));
  EXPECT_NEAR(StatisticEdf(Statistic::kTotal, 0, m, n, 0.01), 1.5 * (n + 1) / m, 1e-9);
  // Phase noise is outside Table 7: SP 1065 Table 5 with N = n + 1 phase points.
  const double np = n + 1.0;
  EXPECT_NEAR(StatisticEdf(Statistic::kTotal, 2, m, n, 0.01),
              (np + 1.0) * (np - 2.0 * m) / (2.0 * (np - m)), 1e-9);
  EXPECT_NEAR(StatisticEdf(Statistic::kTotal, 1, m, n, 0.01),
              std::exp(std::sqrt(std::log((np - 1.0) / (2.0 * m)) *
                                 std::log((2.0 * m + 1.0) * (np - 1.0) / 4.0))),
              1e-9);
}

}  // namespace
}  // namespace allanlab::estimators
