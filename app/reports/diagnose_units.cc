#include "app/reports/diagnose_units.h"

#include "app/input/accel_units.h"
#include "app/input/rate_units.h"
#include "app/reports/sensor_coefficients.h"
#include "sim/units.h"

namespace allanlab::app {
namespace {

bool Accelerometer(const DiagnoseUnits& u) { return u.sensor == ImuSensor::kAccelerometer; }

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

std::string ReportRateUnit(const DiagnoseUnits& u) {
  return Accelerometer(u) ? std::string(AccelUnitName(AccelUnit::kMilliG))
                          : std::string(RateUnitName(RateUnit::kDegPerHour));
}

double ReportRatePerSi(const DiagnoseUnits& u) {
  return Accelerometer(u) ? AccelFromSi(AccelUnit::kMilliG, 1.0) : FromRadPerSecond(RateUnit::kDegPerHour, 1.0);
}

ReportedRate ReportRate(const DiagnoseUnits& u, double si) {
  ReportedRate r{si * ReportRatePerSi(u), ReportRateUnit(u), std::nullopt, ""};
  if (u.record_unit.empty() || u.record_unit == r.unit) return r;
  std::string ignored;
  if (Accelerometer(u)) {
    AccelUnit unit;
    if (!ParseAccelUnit(u.record_unit, &unit, &ignored)) return r;
    r.record_value = AccelFromSi(unit, si);
    r.record_unit = std::string(AccelUnitName(unit));
  } else {
    RateUnit unit;
    if (!ParseRateUnit(u.record_unit, &unit, &ignored)) return r;  // an angle record: deg/h only
    // A gyro's report is in degrees: a record in rad/s gets its rates in deg/h alone, not beside
    // the SI unit the report never uses.
    if (unit == RateUnit::kRadPerSecond) return r;
    r.record_value = FromRadPerSecond(unit, si);
    r.record_unit = std::string(RateUnitName(unit));
  }
  return r;
}

std::string ReportAngleUnit(const DiagnoseUnits& u) { return Accelerometer(u) ? "m/s" : "deg"; }

double ReportAngle(const DiagnoseUnits& u, double si) { return Accelerometer(u) ? si : si / units::kRadPerDeg; }

std::string QuantityWord(const DiagnoseUnits& u) { return Accelerometer(u) ? "acceleration" : "rate"; }

std::string IntegralWord(const DiagnoseUnits& u) { return Accelerometer(u) ? "velocity" : "angle"; }

std::string ParameterName(const DiagnoseUnits& u, const std::string& gyro_name) {
  if (!Accelerometer(u)) return gyro_name;
  if (EndsWith(gyro_name, "_rad_per_s")) return gyro_name.substr(0, gyro_name.size() - 10) + "_m_per_s2";
  if (EndsWith(gyro_name, "_rad")) return gyro_name.substr(0, gyro_name.size() - 4) + "_m_per_s";
  return gyro_name;
}

// Q is an angle (a velocity for an accelerometer): in the report's angle unit, so it reads beside
// the quantizer's LSB (Q = LSB / sqrt(12)), which the report gives in that unit too.
std::string CoefficientUnit(const DiagnoseUnits& u, estimators::Coefficient c) {
  if (c == estimators::Coefficient::kQ) return ReportAngleUnit(u);
  return std::string(SensorDatasheetUnit(u.sensor, c));
}

double CoefficientValue(const DiagnoseUnits& u, estimators::Coefficient c, double value_si) {
  if (c == estimators::Coefficient::kQ) return ReportAngle(u, value_si);
  return SensorDatasheetValue(u.sensor, c, value_si);
}

}  // namespace allanlab::app
