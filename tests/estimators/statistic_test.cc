#include "estimators/statistic.h"

#include <gtest/gtest.h>

#include <string>

namespace allanlab::estimators {
namespace {

constexpr Statistic kAll[] = {
    Statistic::kAllanNonOverlapping,
    Statistic::kAllanOverlapping,
    Statistic::kModifiedAllan,
    Statistic::kHadamardNonOverlapping,
    Statistic::kHadamardOverlapping,
    Statistic::kTotal,
    Statistic::kTime,
};

TEST(Statistic, IdsAreTheDocumentedOnesAndRoundTrip) {
  EXPECT_EQ(StatisticId(Statistic::kAllanNonOverlapping), "nonoverlapping");
  EXPECT_EQ(StatisticId(Statistic::kAllanOverlapping), "overlapping");
  EXPECT_EQ(StatisticId(Statistic::kModifiedAllan), "modified");
  EXPECT_EQ(StatisticId(Statistic::kHadamardNonOverlapping), "hadamard_nonoverlapping");
  EXPECT_EQ(StatisticId(Statistic::kHadamardOverlapping), "hadamard");
  EXPECT_EQ(StatisticId(Statistic::kTotal), "total");
  EXPECT_EQ(StatisticId(Statistic::kTime), "time");
  for (Statistic s : kAll) {
    Statistic parsed = Statistic::kTotal;
    ASSERT_TRUE(ParseStatistic(StatisticId(s), &parsed)) << StatisticId(s);
    EXPECT_EQ(parsed, s);
  }
}

TEST(Statistic, UnknownIdsAreRejectedAndLeaveTheOutputAlone) {
  Statistic s = Statistic::kTime;
  for (const char* bad : {"", "Overlapping", "oadev", "allan", " overlapping", "hadamard "}) {
    EXPECT_FALSE(ParseStatistic(bad, &s)) << bad;
    EXPECT_EQ(s, Statistic::kTime);
  }
}

TEST(Statistic, FactsFollowGreenhallRiley) {
  EXPECT_EQ(DifferenceOrder(Statistic::kAllanNonOverlapping), 2);
  EXPECT_EQ(DifferenceOrder(Statistic::kAllanOverlapping), 2);
  EXPECT_EQ(DifferenceOrder(Statistic::kModifiedAllan), 2);
  EXPECT_EQ(DifferenceOrder(Statistic::kTime), 2);
  EXPECT_EQ(DifferenceOrder(Statistic::kTotal), 2);
  EXPECT_EQ(DifferenceOrder(Statistic::kHadamardNonOverlapping), 3);
  EXPECT_EQ(DifferenceOrder(Statistic::kHadamardOverlapping), 3);

  EXPECT_FALSE(IsOverlapping(Statistic::kAllanNonOverlapping));
  EXPECT_FALSE(IsOverlapping(Statistic::kHadamardNonOverlapping));
  for (Statistic s : {Statistic::kAllanOverlapping, Statistic::kModifiedAllan,
                      Statistic::kHadamardOverlapping, Statistic::kTotal, Statistic::kTime}) {
    EXPECT_TRUE(IsOverlapping(s)) << StatisticId(s);
  }
  for (Statistic s : kAll) {
    EXPECT_EQ(IsModified(s), s == Statistic::kModifiedAllan || s == Statistic::kTime)
        << StatisticId(s);
  }
}

// Stable32's term counts for PHASE.DAT (1001 phase points, 1000 rates), "#" column of its
// octave outputs, and the largest m each statistic allows.
TEST(Statistic, TermCountsMatchStable32) {
  const std::int64_t n = 1000;
  EXPECT_EQ(TermCount(Statistic::kAllanNonOverlapping, 1, n), 999);
  EXPECT_EQ(TermCount(Statistic::kAllanNonOverlapping, 16, n), 61);
  EXPECT_EQ(TermCount(Statistic::kAllanNonOverlapping, 128, n), 6);
  EXPECT_EQ(TermCount(Statistic::kAllanOverlapping, 2, n), 997);
  EXPECT_EQ(TermCount(Statistic::kAllanOverlapping, 128, n), 745);
  EXPECT_EQ(TermCount(Statistic::kModifiedAllan, 2, n), 996);
  EXPECT_EQ(TermCount(Statistic::kModifiedAllan, 128, n), 618);
  EXPECT_EQ(TermCount(Statistic::kTime, 64, n), 810);
  EXPECT_EQ(TermCount(Statistic::kHadamardNonOverlapping, 1, n), 998);
  EXPECT_EQ(TermCount(Statistic::kHadamardNonOverlapping, 128, n), 5);
  EXPECT_EQ(TermCount(Statistic::kHadamardOverlapping, 2, n), 995);
  EXPECT_EQ(TermCount(Statistic::kHadamardOverlapping, 128, n), 617);
  EXPECT_EQ(TermCount(Statistic::kTotal, 256, n), 999);
}

TEST(Statistic, LargestAveragingFactorsAndNothingBeyond) {
  const std::int64_t n = 1000;
  EXPECT_EQ(MaxAveragingFactor(Statistic::kAllanNonOverlapping, n), 500);
  EXPECT_EQ(MaxAveragingFactor(Statistic::kAllanOverlapping, n), 500);
  EXPECT_EQ(MaxAveragingFactor(Statistic::kModifiedAllan, n), 333);
  EXPECT_EQ(MaxAveragingFactor(Statistic::kTime, n), 333);
  EXPECT_EQ(MaxAveragingFactor(Statistic::kHadamardNonOverlapping, n), 333);
  EXPECT_EQ(MaxAveragingFactor(Statistic::kHadamardOverlapping, n), 333);
  EXPECT_EQ(MaxAveragingFactor(Statistic::kTotal, n), 999);
  for (Statistic s : kAll) {
    const std::int64_t max_m = MaxAveragingFactor(s, n);
    EXPECT_GE(TermCount(s, max_m, n), 1) << StatisticId(s);
    EXPECT_EQ(TermCount(s, max_m + 1, n), 0) << StatisticId(s);
    EXPECT_EQ(TermCount(s, 0, n), 0) << StatisticId(s);
    EXPECT_EQ(MaxAveragingFactor(s, 1), 0) << StatisticId(s);
  }
}

}  // namespace
}  // namespace allanlab::estimators
