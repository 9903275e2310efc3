// The units a diagnosis is reported in (app/reports/diagnose_units.h): a gyro's rates in deg/h,
// beside the record's deg/s but never beside rad/s (a gyro's report is in degrees); an
// accelerometer's in mg beside the record's g. Conversions checked against constants written
// here: 1 rad/s = 180/pi deg/s = 648000/pi deg/h; 1 g = 9.80665 m/s^2. Q in the report's angle
// unit (deg; m/s for an accelerometer).
#include "app/reports/diagnose_units.h"

#include <gtest/gtest.h>

#include <cmath>

namespace allanlab::app {
namespace {

TEST(DiagnoseUnits, AGyroRateIsInDegPerHourBesideDegPerSecondNotRadPerSecond) {
  const double si = 1e-4;  // rad/s
  const ReportedRate deg_s = ReportRate({ImuSensor::kGyro, "deg/s"}, si);
  EXPECT_EQ(deg_s.unit, "deg/h");
  EXPECT_NEAR(deg_s.value, si * 648000.0 / M_PI, 1e-12);
  ASSERT_TRUE(deg_s.record_value.has_value());
  EXPECT_EQ(deg_s.record_unit, "deg/s");
  EXPECT_NEAR(*deg_s.record_value, si * 180.0 / M_PI, 1e-15);
  const ReportedRate rad_s = ReportRate({ImuSensor::kGyro, "rad/s"}, si);
  EXPECT_EQ(rad_s.unit, "deg/h");
  EXPECT_NEAR(rad_s.value, si * 648000.0 / M_PI, 1e-12);
  EXPECT_FALSE(rad_s.record_value.has_value()) << rad_s.record_unit;
  EXPECT_FALSE(ReportRate({ImuSensor::kGyro, "deg/h"}, si).record_value.has_value());  // the report's own
}

TEST(DiagnoseUnits, AnAccelerometerIsInMilliGBesideTheRecordsG) {
  const ReportedRate r = ReportRate({ImuSensor::kAccelerometer, "g"}, 0.0980665);
  EXPECT_EQ(r.unit, "mg");
  EXPECT_NEAR(r.value, 10.0, 1e-12);
  ASSERT_TRUE(r.record_value.has_value());
  EXPECT_EQ(r.record_unit, "g");
  EXPECT_NEAR(*r.record_value, 0.01, 1e-15);
}

// Q is an angle: a gyro's in deg, like the quantizer's LSB the report prints beside it (not the
// fit table's urad); an accelerometer's a velocity in m/s. The other coefficients keep their
// data-sheet units.
TEST(DiagnoseUnits, QuantizationIsInTheReportsAngleUnit) {
  const DiagnoseUnits gyro{ImuSensor::kGyro, "deg/s"};
  EXPECT_EQ(CoefficientUnit(gyro, estimators::Coefficient::kQ), "deg");
  EXPECT_NEAR(CoefficientValue(gyro, estimators::Coefficient::kQ, 1e-6), 1e-6 * 180.0 / M_PI, 1e-18);
  EXPECT_EQ(CoefficientUnit(gyro, estimators::Coefficient::kB), "deg/h");
  EXPECT_NEAR(CoefficientValue(gyro, estimators::Coefficient::kB, 1e-5), 1e-5 * 648000.0 / M_PI, 1e-9);
  const DiagnoseUnits accel{ImuSensor::kAccelerometer, "g"};
  EXPECT_EQ(CoefficientUnit(accel, estimators::Coefficient::kQ), "m/s");
  EXPECT_DOUBLE_EQ(CoefficientValue(accel, estimators::Coefficient::kQ, 2e-4), 2e-4);
}

}  // namespace
}  // namespace allanlab::app
