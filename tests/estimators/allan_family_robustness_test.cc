// A constant rate offset of 1e4 x the noise level on a 1e7-sample record changes no statistic
// beyond 1e-9 relative (allan_family.h: prefix sums of the mean-removed record). Without the
// mean removal the phase would reach ~1e11 x the noise and the differences would keep ~5 digits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "estimators/allan_family.h"

namespace allanlab::estimators {
namespace {

TEST(AllanFamilyRobustness, LargeConstantOffsetChangesNothing) {
  constexpr std::int64_t kSamples = 10'000'000;
  constexpr double kNoise = 2.5e-3;  // white rate noise, rad/s
  constexpr double kOffset = 1e4 * kNoise;
  std::mt19937_64 engine(20240601);
  std::normal_distribution<double> normal(0.0, kNoise);
  std::vector<double> rate(kSamples), biased(kSamples);
  for (std::int64_t k = 0; k < kSamples; ++k) {
    rate[k] = normal(engine);
    biased[k] = rate[k] + kOffset;
  }
  for (Statistic s : {Statistic::kAllanNonOverlapping, Statistic::kAllanOverlapping,
                      Statistic::kModifiedAllan, Statistic::kHadamardNonOverlapping,
                      Statistic::kHadamardOverlapping, Statistic::kTotal, Statistic::kTime}) {
    AvarOptions options;
    options.statistic = s;
    options.sample_clock = SampleClock::FromPeriodS(0.005);
    AvarSummary plain, offset;
    ASSERT_TRUE(ComputeStatisticValues(options, rate, &plain)) << plain.message;
    ASSERT_TRUE(ComputeStatisticValues(options, biased, &offset)) << offset.message;
    ASSERT_EQ(plain.points.size(), offset.points.size());
    ASSERT_GE(plain.points.size(), 20u);
    double worst = 0.0;
    for (std::size_t k = 0; k < plain.points.size(); ++k) {
      const double a = plain.points[k].value, b = offset.points[k].value;
      EXPECT_NEAR(b, a, 1e-9 * a) << StatisticId(s) << " m=" << plain.points[k].m;
      worst = std::max(worst, std::abs(b - a) / a);
    }
    std::printf("%-24s largest relative change %.2e\n", std::string(StatisticId(s)).c_str(), worst);
  }
}

}  // namespace
}  // namespace allanlab::estimators
