#include "common/sample_clock.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace allanlab {
namespace {

// 49 Hz is a rate whose period does not invert back to it in double precision
// (1 / (1 / 49) = 49.000000000000007): a carrier that kept only the period would hand a sensor
// model a different rate from the one the user gave.
TEST(SampleClock, KeepsTheRateItWasGivenExactly) {
  ASSERT_NE(1.0 / (1.0 / 49.0), 49.0);
  const SampleClock clock = SampleClock::FromRateHz(49.0);
  EXPECT_EQ(clock.rate_hz(), 49.0);
  EXPECT_EQ(clock.period_s(), 1.0 / 49.0);
  EXPECT_TRUE(clock.IsValid());
}

TEST(SampleClock, KeepsThePeriodItWasGivenExactly) {
  const double period_s = 1.0 / 49.0;
  const SampleClock clock = SampleClock::FromPeriodS(period_s);
  EXPECT_EQ(clock.period_s(), period_s);
  EXPECT_EQ(clock.rate_hz(), 1.0 / period_s);
}

TEST(SampleClock, DefaultIsOneHertz) {
  const SampleClock clock;
  EXPECT_EQ(clock.rate_hz(), 1.0);
  EXPECT_EQ(clock.period_s(), 1.0);
}

TEST(SampleClock, ZeroNegativeAndNonFiniteAreInvalid) {
  EXPECT_FALSE(SampleClock::FromRateHz(0.0).IsValid());
  EXPECT_FALSE(SampleClock::FromRateHz(-100.0).IsValid());
  EXPECT_FALSE(SampleClock::FromPeriodS(0.0).IsValid());
  EXPECT_FALSE(SampleClock::FromRateHz(std::numeric_limits<double>::quiet_NaN()).IsValid());
  EXPECT_FALSE(SampleClock::FromRateHz(std::numeric_limits<double>::infinity()).IsValid());
  EXPECT_FALSE(SampleClock::FromPeriodS(std::numeric_limits<double>::infinity()).IsValid());
}

TEST(SampleClock, ClocksMadeFromTheSameRateAreEqual) {
  EXPECT_EQ(SampleClock::FromRateHz(400.0), SampleClock::FromRateHz(400.0));
  EXPECT_NE(SampleClock::FromRateHz(400.0), SampleClock::FromRateHz(200.0));
}

}  // namespace
}  // namespace allanlab
