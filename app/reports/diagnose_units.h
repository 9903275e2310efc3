#pragma once
// The units a diagnosis is reported in, chosen by the column's sensor. The diagnosis itself works
// in SI and never looks at the unit (docs/theory.md §1): a gyro's record is in rad/s, an
// accelerometer's in m/s^2, and an effect's parameters are named for the gyro (size_rad_per_s,
// lsb_rad). Reported:
//   gyro           rates in deg/h (and the record's rate unit), angles in deg
//   accelerometer  accelerations in mg (and the record's unit), velocities in m/s
// and the coefficients N, B, K, R as app/reports/sensor_coefficients.h prints them, Q in the
// report's angle (velocity) unit.
#include <optional>
#include <string>

#include "app/input/imu_columns.h"
#include "estimators/fit/noise_coefficient.h"

namespace allanlab::app {

struct DiagnoseUnits {
  ImuSensor sensor = ImuSensor::kGyro;
  // The unit the record was read in ("deg/s", "g", ...); empty: report in the report unit only.
  std::string record_unit;
};

// A rate-like quantity (a gyro's rate, an accelerometer's acceleration) in the report's unit.
struct ReportedRate {
  double value = 0.0;
  std::string unit;  // "deg/h" or "mg"
  // The same quantity in the record's unit, when that differs from the report's (a gyro
  // record's deg/s; not rad/s: a gyro's report is in degrees).
  std::optional<double> record_value;
  std::string record_unit;
};
ReportedRate ReportRate(const DiagnoseUnits& units, double si);

// The report's unit of a rate-like quantity ("deg/h", "mg"), and its value per SI unit.
std::string ReportRateUnit(const DiagnoseUnits& units);
double ReportRatePerSi(const DiagnoseUnits& units);

// An integrated quantity (a gyro's angle, an accelerometer's velocity): unit and value.
std::string ReportAngleUnit(const DiagnoseUnits& units);
double ReportAngle(const DiagnoseUnits& units, double si);

// "rate" or "acceleration": what the record holds, in words.
std::string QuantityWord(const DiagnoseUnits& units);
// "angle" or "velocity": its integral, in words.
std::string IntegralWord(const DiagnoseUnits& units);

// An effect parameter's SI name for this sensor: a gyro's as the diagnosis names it
// (size_rad_per_s, lsb_rad); an accelerometer's with its own SI unit (size_m_per_s2, lsb_m_per_s).
std::string ParameterName(const DiagnoseUnits& units, const std::string& gyro_name);

// A coefficient as the sensor's data sheet gives it.
std::string CoefficientUnit(const DiagnoseUnits& units, estimators::Coefficient c);
double CoefficientValue(const DiagnoseUnits& units, estimators::Coefficient c, double value_si);

}  // namespace allanlab::app
