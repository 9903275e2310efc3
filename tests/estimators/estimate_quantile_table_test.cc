// The tabulated quantiles (estimators/estimate_quantile_table.h) are the bits the computation
// gives: entries across the table recomputed here (every entry: the _slow_ test beside this one),
// and EstimateQuantilesAt, which reads the table, against ComputeEstimateQuantiles at the taus
// of real records, including the ones the table does not hold.
#include <gtest/gtest.h>

#include <cstring>

#include "estimators/estimate_quantile_table.h"

namespace allanlab::estimators {
namespace {

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void ExpectSame(const EstimateQuantiles& a, const EstimateQuantiles& b, const std::string& what) {
  EXPECT_EQ(a.ok, b.ok) << what;
  EXPECT_TRUE(SameBits(a.low, b.low)) << what << ": " << a.low << " " << b.low;
  EXPECT_TRUE(SameBits(a.high, b.high)) << what << ": " << a.high << " " << b.high;
}

TEST(EstimateQuantileTable, EntriesAreTheComputedBits) {
  for (int alpha = 0; alpha >= -2; --alpha) {
    for (std::int64_t n = kTabulatedShortestRecord; n <= kTabulatedLongestRecord; n += 15) {
      const auto table = TabulatedEstimateQuantiles(Statistic::kAllanOverlapping, alpha, 32, 2 * n, 0.683);
      ASSERT_TRUE(table.has_value()) << n;
      ExpectSame(*table, ComputeEstimateQuantiles(Statistic::kAllanOverlapping, alpha, 32, 2 * n, 0.683),
                 "alpha " + std::to_string(alpha) + ", reduced length " + std::to_string(n));
    }
  }
}

// The points `avar` asks about: octave m with at most 16 clusters on records of many lengths.
TEST(EstimateQuantileTable, AvarPointsReadTheComputedBits) {
  int tabulated = 0;
  for (const std::int64_t n : {std::int64_t{1000}, std::int64_t{65536}, std::int64_t{1000003},
                               std::int64_t{10000000}, std::int64_t{100000000}}) {
    for (std::int64_t m = 1; m <= n / 2; m *= 2) {
      if (n / m > kDistributionIntervalMaxClusters) continue;
      for (int alpha = 2; alpha >= -2; --alpha) {
        tabulated += TabulatedEstimateQuantiles(Statistic::kAllanOverlapping, alpha, m, n, 0.683).has_value();
        ExpectSame(EstimateQuantilesAt(Statistic::kAllanOverlapping, alpha, m, n, 0.683),
                   ComputeEstimateQuantiles(Statistic::kAllanOverlapping, alpha, m, n, 0.683),
                   "n " + std::to_string(n) + ", m " + std::to_string(m) + ", alpha " + std::to_string(alpha));
      }
    }
  }
  EXPECT_GT(tabulated, 20);
}

TEST(EstimateQuantileTable, OnlyTheTabulatedCasesAreRead) {
  EXPECT_FALSE(TabulatedEstimateQuantiles(Statistic::kAllanOverlapping, 0, 1 << 20, 10000000, 0.95));
  EXPECT_FALSE(TabulatedEstimateQuantiles(Statistic::kHadamardOverlapping, 0, 1 << 20, 10000000, 0.683));
  EXPECT_FALSE(TabulatedEstimateQuantiles(Statistic::kAllanOverlapping, 1, 1 << 20, 10000000, 0.683));
  EXPECT_FALSE(TabulatedEstimateQuantiles(Statistic::kAllanOverlapping, 0, 16, 200, 0.683));  // not reduced
  EXPECT_FALSE(TabulatedEstimateQuantiles(Statistic::kAllanOverlapping, 0, 1 << 10, 1 << 15, 0.683));  // 32 clusters
  EXPECT_TRUE(TabulatedEstimateQuantiles(Statistic::kAllanOverlapping, 0, 1 << 20, 10000000, 0.683));
}

}  // namespace
}  // namespace allanlab::estimators
