// What a column name or a unit text says about the units of a record, and how the statements
// meet --units.
#include "app/input/stated_units.h"

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

namespace allanlab::app {
namespace {

using estimators::InputKind;

std::string FromName(const std::string& name, InputKind kind = InputKind::kRate) {
  std::optional<StatedUnit> unit;
  std::string why;
  if (!UnitFromColumnName(name, kind, &unit, &why)) return "error: " + why;
  return unit ? unit->unit : "";
}

TEST(StatedUnitsTest, RateUnitsFromColumnNames) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"rate_rad_per_s", "rad/s"},  {"rate_deg_per_s", "deg/s"},   {"rate_deg_per_h", "deg/h"},
      {"gyro_x_rad_s", "rad/s"},    {"Gyro_X_dps", "deg/s"},       {"wz_radps", "rad/s"},
      {"gyro_z_dph", "deg/h"},      {"Gyro X [deg/s]", "deg/s"},   {"wx (rad/s)", "rad/s"},
      {"omega_z[°/h]", "deg/h"},    {"gyro_x_deg_per_sec", "deg/s"}, {"GYRO_Y_RAD_PER_S", "rad/s"},
      {"gyro_dps_x", "deg/s"},      {"field.angular_velocity.x", "rad/s"},
      {"rate_deg_hr", "deg/h"},
      // Nothing about units: no statement.
      {"Gyro_X", ""},               {"gyro_x", ""},                {"column", ""},
      {"x_s", ""},                  {"degradation", ""},           {"rads", ""},
  };
  for (const auto& [name, expected] : cases) EXPECT_EQ(FromName(name), expected) << name;
}

TEST(StatedUnitsTest, UnitsAllanlabDoesNotConvertAreRefused) {
  for (const std::string name : {"gyro_x_mdps", "gyro_x_mrad_s", "rate_rad_per_h"}) {
    const std::string got = FromName(name);
    EXPECT_EQ(got.rfind("error: column " + name + " states ", 0), 0u) << got;
    EXPECT_NE(got.find("does not convert"), std::string::npos) << got;
  }
}

TEST(StatedUnitsTest, AngleColumns) {
  EXPECT_EQ(FromName("angle_deg", InputKind::kAngle), "deg");
  EXPECT_EQ(FromName("theta_rad", InputKind::kAngle), "rad");
  EXPECT_EQ(FromName("phase_arcsec", InputKind::kAngle), "arcsec");
  EXPECT_EQ(FromName("angle", InputKind::kAngle), "");
  // An angle word in a rate column says nothing (rate_deg could be anything).
  EXPECT_EQ(FromName("rate_deg"), "");
  // A rate column read as angle is a mistake worth stopping.
  EXPECT_EQ(FromName("rate_deg_per_s", InputKind::kAngle).rfind("error: column rate_deg_per_s "
                                                                "holds a rate (deg/s)", 0),
            0u);
}

TEST(StatedUnitsTest, CanonicalSpellings) {
  std::string unit, why;
  for (const auto& [text, expected] : std::vector<std::pair<std::string, std::string>>{
           {"deg/s", "deg/s"}, {"rad/s", "rad/s"}, {"deg/h", "deg/h"}, {"°/s", "deg/s"},
           {"dps", "deg/s"}, {"rad/sec", "rad/s"}, {"deg/hr", "deg/h"}, {"DEG/S", "deg/s"}}) {
    ASSERT_TRUE(CanonicalUnit(text, InputKind::kRate, &unit, &why)) << text << ": " << why;
    EXPECT_EQ(unit, expected) << text;
  }
  EXPECT_FALSE(CanonicalUnit("deg/min", InputKind::kRate, &unit, &why));
  EXPECT_EQ(why, "unknown rate unit 'deg/min' (expected deg/s, deg/h or rad/s)");
  EXPECT_FALSE(CanonicalUnit("deg/s per bit", InputKind::kRate, &unit, &why));
  EXPECT_FALSE(CanonicalUnit("g", InputKind::kRate, &unit, &why));
  EXPECT_FALSE(CanonicalUnit("deg/s", InputKind::kAngle, &unit, &why));
  ASSERT_TRUE(CanonicalUnit("arcsec", InputKind::kAngle, &unit, &why));
  EXPECT_EQ(unit, "arcsec");
}

TEST(StatedUnitsTest, StatementsMustAgreeAndOneMustExist) {
  StatedUnit resolved;
  std::string why;
  ASSERT_TRUE(ResolveUnits({{"rad/s", "column rate_rad_per_s"}, {"rad/s", "--units"}},
                           InputKind::kRate, "column rate_rad_per_s", &resolved, &why));
  EXPECT_EQ(resolved.unit, "rad/s");
  EXPECT_EQ(resolved.source, "column rate_rad_per_s");

  EXPECT_FALSE(ResolveUnits({{"rad/s", "column rate_rad_per_s"}, {"deg/s", "--units"}},
                            InputKind::kRate, "column rate_rad_per_s", &resolved, &why));
  EXPECT_EQ(why, "--units (deg/s) contradicts column rate_rad_per_s (rad/s): drop --units or "
                 "correct it");
  EXPECT_FALSE(ResolveUnits({{"rad/s", "column w_rad_s"}, {"deg/s", "the '# units: deg/s' line"}},
                            InputKind::kRate, "column w_rad_s", &resolved, &why));
  EXPECT_EQ(why, "the '# units: deg/s' line (deg/s) contradicts column w_rad_s (rad/s)");

  EXPECT_FALSE(ResolveUnits({}, InputKind::kRate, "column Gyro_X", &resolved, &why));
  EXPECT_EQ(why, "the units of column Gyro_X are not stated in the file (a unit in the column "
                 "name such as _dps or _rad_s, or a '# units:' line): give --units deg/s, deg/h "
                 "or rad/s");
}

}  // namespace
}  // namespace allanlab::app
