// A stuck stretch of a record is found where it is, and named only when it is long enough to
// matter (>= 100 samples and >= 0.1 % of the record). The record reader feeds the same tracker.
#include "app/input/constant_stretch.h"

#include <algorithm>
#include <random>
#include <span>
#include <vector>

#include <gtest/gtest.h>

namespace allanlab::app {
namespace {

std::vector<double> Ramp(int n) {
  std::vector<double> v;
  for (int k = 0; k < n; ++k) v.push_back(0.001 * k);
  return v;
}

TEST(ConstantStretch, FindsTheLongestRunWherever) {
  EXPECT_EQ(LongestConstantStretch({}).length, 0);
  std::vector<double> v = Ramp(1000);
  EXPECT_EQ(LongestConstantStretch(v).length, 1);
  for (int k = 200; k < 260; ++k) v[k] = 5.0;
  for (int k = 990; k < 1000; ++k) v[k] = -1.0;  // shorter, at the very end
  ConstantStretch s = LongestConstantStretch(v);
  EXPECT_EQ(s.first, 200);
  EXPECT_EQ(s.length, 60);
  EXPECT_EQ(s.value, 5.0);
  for (int k = 900; k < 1000; ++k) v[k] = -1.0;  // the longest now ends the record
  s = LongestConstantStretch(v);
  EXPECT_EQ(s.first, 900);
  EXPECT_EQ(s.length, 100);
}

// Blocks of any size give what one comparison per sample gives, checked against the longest run
// counted here directly, on records with runs (some across block edges) among distinct values.
TEST(ConstantStretch, BlocksFindTheSameRun) {
  std::mt19937_64 engine(3);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<double> v = Ramp(1 + static_cast<int>(engine() % 3000));
    for (int runs = static_cast<int>(engine() % 4); runs > 0; --runs) {
      const std::size_t at = engine() % v.size(), length = 1 + engine() % 150;
      for (std::size_t k = at; k < std::min(v.size(), at + length); ++k) v[k] = v[at];
    }
    ConstantStretch expected;
    for (std::size_t k = 0, start = 0; k < v.size(); ++k) {
      if (k > 0 && v[k] != v[k - 1]) start = k;
      if (static_cast<std::int64_t>(k - start + 1) > expected.length) {
        expected = {static_cast<std::int64_t>(start), static_cast<std::int64_t>(k - start + 1), v[k]};
      }
    }
    ConstantStretchTracker tracker;
    for (std::size_t k = 0; k < v.size();) {
      const std::size_t n = std::min(v.size() - k, static_cast<std::size_t>(engine() % 300));
      tracker.AddBlock(std::span<const double>(v).subspan(k, n));
      k += n;
    }
    EXPECT_EQ(tracker.longest().first, expected.first) << trial;
    EXPECT_EQ(tracker.longest().length, expected.length) << trial;
    EXPECT_EQ(tracker.longest().value, expected.value) << trial;
  }
}

TEST(ConstantStretch, NamedOnlyWhenLongEnough) {
  std::vector<double> v = Ramp(200000);
  auto describe = [&] { return DescribeConstantStretch(LongestConstantStretch(v), 200000, 100.0); };
  for (int k = 1000; k < 1099; ++k) v[k] = 0.0;  // 99 samples: below the floor
  EXPECT_FALSE(describe());
  for (int k = 1000; k < 1150; ++k) v[k] = 0.0;  // 150 samples but < 0.1 % of 200000
  EXPECT_FALSE(describe());
  for (int k = 1000; k < 1400; ++k) v[k] = 0.0;  // 400 samples = 0.2 %: named, in seconds
  const auto text = describe();
  ASSERT_TRUE(text);
  EXPECT_NE(text->find("400 identical samples"), std::string::npos) << *text;
  EXPECT_NE(text->find("4 s from sample 1000"), std::string::npos) << *text;
}

}  // namespace
}  // namespace allanlab::app
