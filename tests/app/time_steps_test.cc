#include "app/input/time_steps.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

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

namespace allanlab::app {
namespace {

// The grouping rule written out once more, step by step (the reference for Add, whose common
// step is taken inline): every field of the summary must match it exactly.
struct ReferenceSteps {
  struct Group {
    double sum = 0.0;
    std::int64_t count = 0;
  };
  std::vector<Group> groups;
  std::int64_t samples = 0;
  double previous = 0.0, largest = 0.0, smallest = 0.0;
  std::int64_t largest_line = 0, smallest_line = 0;
  void Add(double t, std::int64_t line) {
    if (samples > 0) {
      const double step = t - previous;
      if (samples == 1 || step > largest) {
        largest = step;
        largest_line = line;
      }
      if (samples == 1 || step < smallest) {
        smallest = step;
        smallest_line = line;
      }
      bool placed = false;
      for (Group& g : groups) {
        if (std::abs(step * static_cast<double>(g.count) - g.sum) <= TimeSteps::kStepTolerance * g.sum) {
          g.sum += step;
          ++g.count;
          placed = true;
          break;
        }
      }
      if (!placed && static_cast<int>(groups.size()) < TimeSteps::kMaxGroups) groups.push_back({step, 1});
    }
    previous = t;
    ++samples;
  }
};

TEST(TimeStepsTest, EveryStepCountsAsTheGroupingRuleSays) {
  std::mt19937_64 rng(5);
  for (int record = 0; record < 200; ++record) {
    TimeSteps steps;
    ReferenceSteps reference;
    double t = 1000.0 * static_cast<double>(rng() % 7);
    const double period = record % 3 == 0 ? 0.01 : record % 3 == 1 ? 1.0 / 3.0 : 0.005;
    std::string why;
    for (std::int64_t line = 2; line < 5000; ++line) {
      const unsigned kind = static_cast<unsigned>(rng() % 1000);
      double step = period * (1.0 + 1e-5 * (static_cast<double>(rng() % 201) - 100.0));  // jitter
      if (kind < 3) step = period * static_cast<double>(2 + rng() % 5);                  // a gap
      if (kind == 3) step = period * 0.5;                                               // a short step
      if (kind == 4) step = period * (1.0 + 2e-3);                                      // just outside
      if (record % 17 == 0 && kind < 600) step = period * static_cast<double>(1 + rng() % 3);
      t += step;
      ASSERT_TRUE(steps.Add(t, line, &why)) << why;
      reference.Add(t, line);
    }
    const TimeSteps::Summary s = steps.Summarize();
    const ReferenceSteps::Group* best = &reference.groups.front();
    for (const auto& g : reference.groups) {
      if (g.count > best->count) best = &g;
    }
    EXPECT_EQ(s.samples, reference.samples);
    EXPECT_EQ(s.nominal_step_s, best->sum / static_cast<double>(best->count)) << record;
    EXPECT_EQ(s.irregular_steps, reference.samples - 1 - best->count) << record;
    EXPECT_EQ(s.largest_step_s, reference.largest) << record;
    EXPECT_EQ(s.largest_step_line, reference.largest_line) << record;
    EXPECT_EQ(s.smallest_step_s, reference.smallest) << record;
    EXPECT_EQ(s.smallest_step_line, reference.smallest_line) << record;
  }
}

}  // namespace
}  // namespace allanlab::app
