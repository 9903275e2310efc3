// Every entry of the tabulated quantiles (estimators/estimate_quantile_table.h) recomputed:
// the table is the bits ComputeEstimateQuantiles gives today (about 15 s).
#include <gtest/gtest.h>

#include <cstring>

#include "estimators/estimate_quantile_table.h"

namespace allanlab::estimators {
namespace {

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(EstimateQuantileTableSlow, EveryEntryIsTheComputedBits) {
  for (int alpha = 0; alpha >= -2; --alpha) {
    for (std::int64_t n = kTabulatedShortestRecord; n <= kTabulatedLongestRecord; ++n) {
      const auto table = TabulatedEstimateQuantiles(Statistic::kAllanOverlapping, alpha, 32, 2 * n, 0.683);
      const EstimateQuantiles computed =
          ComputeEstimateQuantiles(Statistic::kAllanOverlapping, alpha, 32, 2 * n, 0.683);
      ASSERT_TRUE(table.has_value());
      EXPECT_EQ(table->ok, computed.ok) << alpha << " " << n;
      EXPECT_TRUE(SameBits(table->low, computed.low) && SameBits(table->high, computed.high))
          << "alpha " << alpha << ", reduced length " << n;
    }
  }
}

}  // namespace
}  // namespace allanlab::estimators
