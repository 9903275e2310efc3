#include "app/input/time_steps.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace allanlab::app {
namespace {

TEST(TimeStepsTest, RegularDecimalTimestampsHaveOneGroup) {
  TimeSteps steps;
  std::string why;
  // Printed with two decimals, as real files are: steps differ from 0.01 in the last bits.
  for (int k = 0; k < 100000; ++k) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f", k / 100.0);
    ASSERT_TRUE(steps.Add(std::strtod(text, nullptr), k + 2, &why)) << why;
  }
  const TimeSteps::Summary s = steps.Summarize();
  EXPECT_EQ(s.samples, 100000);
  EXPECT_NEAR(s.nominal_step_s, 0.01, 1e-12);
  EXPECT_EQ(s.irregular_steps, 0);
}

TEST(TimeStepsTest, GapsAreCountedAndTheWorstIsKept) {
  TimeSteps steps;
  std::string why;
  double t = 0;
  for (int k = 0; k < 100; ++k) {
    t += (k == 40) ? 0.5 : (k == 70 ? 0.03 : 0.1);
    ASSERT_TRUE(steps.Add(t, k + 1, &why)) << why;
  }
  const TimeSteps::Summary s = steps.Summarize();
  EXPECT_NEAR(s.nominal_step_s, 0.1, 1e-12);
  EXPECT_EQ(s.irregular_steps, 2);
  EXPECT_NEAR(s.largest_step_s, 0.5, 1e-12);
  EXPECT_EQ(s.largest_step_line, 41);
  EXPECT_NEAR(s.smallest_step_s, 0.03, 1e-12);
  EXPECT_EQ(s.smallest_step_line, 71);
}

TEST(TimeStepsTest, DescribeRoundsAndNamesOnlyOffNominalExtremes) {
  TimeSteps steps;
  std::string why;
  for (double t : {0.0, 0.1, 0.2, 0.30000000000000004, 1.4, 1.5}) {
    ASSERT_TRUE(steps.Add(t, static_cast<std::int64_t>(t * 10) + 2, &why)) << why;
  }
  EXPECT_EQ(TimeSteps::Describe(steps.Summarize(), "t"),
            "1 irregular time step(s) in t (nominal 0.1 s; largest 1.1 s at line 16)");
}

TEST(TimeStepsTest, NotIncreasingOrNotFiniteFails) {
  TimeSteps steps;
  std::string why;
  ASSERT_TRUE(steps.Add(1.0, 3, &why));
  ASSERT_TRUE(steps.Add(2.0, 4, &why));
  EXPECT_FALSE(steps.Add(2.0, 5, &why));
  EXPECT_EQ(why,
            "time is not increasing: line 5 has t = 2 s after t = 2 s at line 4 (sort the record "
            "first)");
  EXPECT_FALSE(steps.Add(NAN, 6, &why));
  EXPECT_EQ(why, "line 6: time nan is not a finite number");
}

TEST(TimeStepsTest, WildTimestampsUseBoundedMemory) {
  TimeSteps steps;
  std::string why;
  double t = 0;
  for (int k = 0; k < 10000; ++k) {
    t += 1.0 + (k % 997) * 0.01;  // hundreds of distinct steps
    ASSERT_TRUE(steps.Add(t, k, &why));
  }
  const TimeSteps::Summary s = steps.Summarize();
  EXPECT_GT(s.irregular_steps, 9000);
  EXPECT_EQ(s.samples, 10000);
}

}  // namespace
}  // namespace allanlab::app
