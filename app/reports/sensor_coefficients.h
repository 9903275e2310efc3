#pragma once
// The Allan coefficients Q, N, B, K, R of a gyro or an accelerometer axis, as printed: the name a
// data sheet gives each one and its datasheet unit. A gyro's are estimators/fit/noise_coefficient.h
// (Q urad, N deg/sqrt(h), B deg/h, K deg/h/sqrt(h), R deg/h^2), an accelerometer's
// app/input/accel_units.h (Q m/s, VRW N m/s/sqrt(h), B mg, K m/s^2/sqrt(h), R m/s^2/h).
#include <string>
#include <string_view>

#include "app/input/imu_columns.h"
#include "estimators/fit/noise_coefficient.h"
#include "estimators/fit/parametric_term.h"

namespace allanlab::app {

// "angle random walk (ARW)", "velocity random walk (VRW)", "bias instability", ...
std::string_view SensorCoefficientName(ImuSensor sensor, estimators::Coefficient c);
std::string_view SensorDatasheetUnit(ImuSensor sensor, estimators::Coefficient c);
double SensorDatasheetValue(ImuSensor sensor, estimators::Coefficient c, double value_si);

// "accelerometer: Q velocity quantization, N velocity random walk (VRW), ...": the key printed above
// an accelerometer's table, whose rows are named Q, N, B, K, R as a gyro's.
std::string AccelerometerTermsLine();

// A parametric term's parameter as printed for this sensor: a gyro's as the term states it; an
// accelerometer's rate-valued parameter (GM sigma, H Omega0, stated in deg/h) in mg instead.
struct ParameterUnit {
  std::string unit;
  double si_per_unit = 1.0;
};
ParameterUnit SensorParameterUnit(ImuSensor sensor, const estimators::ParameterSpec& spec);

}  // namespace allanlab::app
