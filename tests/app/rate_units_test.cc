#include "app/input/rate_units.h"

#include <gtest/gtest.h>

#include <string>

#include "sim/units.h"

namespace allanlab::app {
namespace {

TEST(RateUnitsTest, NamesRoundTripThroughTheParser) {
  for (RateUnit unit : {RateUnit::kDegPerSecond, RateUnit::kDegPerHour, RateUnit::kRadPerSecond}) {
    RateUnit parsed = RateUnit::kRadPerSecond;
    std::string why;
    ASSERT_TRUE(ParseRateUnit(RateUnitName(unit), &parsed, &why)) << why;
    EXPECT_EQ(parsed, unit);
  }
  EXPECT_EQ(RateUnitIdentifier(RateUnit::kDegPerSecond), "deg_per_s");
  EXPECT_EQ(RateUnitIdentifier(RateUnit::kDegPerHour), "deg_per_h");
  EXPECT_EQ(RateUnitIdentifier(RateUnit::kRadPerSecond), "rad_per_s");
}

TEST(RateUnitsTest, UnknownUnitIsRejectedWithTheChoices) {
  RateUnit unit;
  std::string why;
  EXPECT_FALSE(ParseRateUnit("deg/min", &unit, &why));
  EXPECT_NE(why.find("deg/min"), std::string::npos) << why;
  EXPECT_NE(why.find("deg/h"), std::string::npos) << why;
  EXPECT_FALSE(ParseRateUnit("", &unit, &why));
  EXPECT_FALSE(ParseRateUnit("DEG/S", &unit, &why));
}

TEST(RateUnitsTest, ConversionsAgreeWithSimUnits) {
  const double rate = units::DegPerSecond(1.5);
  EXPECT_DOUBLE_EQ(FromRadPerSecond(RateUnit::kDegPerSecond, rate), 1.5);
  EXPECT_DOUBLE_EQ(FromRadPerSecond(RateUnit::kDegPerHour, rate), 1.5 * 3600.0);
  EXPECT_EQ(FromRadPerSecond(RateUnit::kRadPerSecond, rate), rate);
}

TEST(RateUnitsTest, ToRadPerSecondInvertsFromRadPerSecond) {
  EXPECT_EQ(ToRadPerSecond(RateUnit::kDegPerSecond, 180.0), units::kPi);
  EXPECT_EQ(ToRadPerSecond(RateUnit::kRadPerSecond, 0.25), 0.25);
  for (RateUnit unit : {RateUnit::kDegPerSecond, RateUnit::kDegPerHour, RateUnit::kRadPerSecond}) {
    const double v = 0.123456789;
    EXPECT_NEAR(FromRadPerSecond(unit, ToRadPerSecond(unit, v)), v, 1e-16) << RateUnitName(unit);
  }
}

}  // namespace
}  // namespace allanlab::app
