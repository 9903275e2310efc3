#pragma once
// Accelerometer units at the file edge (inside allanlab an accelerometer sample is in m/s^2, as a
// gyro sample is in rad/s). One g is the standard gravity 9.80665 m/s^2 (CGPM 1901), the
// convention of accelerometer data sheets, not the local gravity.
//
// The Allan coefficients of an accelerometer are those of a gyro with rate replaced by
// acceleration (docs/theory.md §1: the estimators never look at the unit):
//   Q  velocity quantization          m/s          (SI m/s)
//   N  velocity random walk (VRW)     m/s/sqrt(h)  (SI m/s/sqrt(s) = m/s^2/sqrt(Hz))
//   B  bias instability               mg           (SI m/s^2)
//   K  acceleration random walk       m/s^2/sqrt(h)(SI m/s^2/sqrt(s) = m/s^3/sqrt(Hz))
//   R  acceleration ramp              m/s^2/h      (SI m/s^3)
#include <span>
#include <string>
#include <string_view>

#include "estimators/fit/noise_coefficient.h"

namespace allanlab::app {

inline constexpr double kStandardGravity = 9.80665;  // m/s^2 per g

enum class AccelUnit { kMeterPerSecond2, kG, kMilliG };

// Accepts "m/s^2" (also "m/s2", "m/s²", "mps2", "m s^-2"), "g" and "mg" (case-insensitive);
// anything else is false with a message listing them.
bool ParseAccelUnit(std::string_view text, AccelUnit* unit, std::string* why);
// "m/s^2", "g", "mg": the canonical spelling, for messages, provenance and column names.
std::string_view AccelUnitName(AccelUnit unit);
// "m_per_s2", "g", "mg": for JSON keys and CSV column names.
std::string_view AccelUnitIdentifier(AccelUnit unit);

double AccelToSi(AccelUnit unit, double value);
void AccelToSi(AccelUnit unit, std::span<double> values);
double AccelFromSi(AccelUnit unit, double m_per_s2);

// The unit a column name states for an accelerometer axis ("Accel_X_g", "acc_x_mps2",
// "az [m/s^2]", "linear_acceleration.x" of a ROS sensor_msgs/Imu, which is m/s^2 by definition);
// empty when the name says nothing about units.
std::string AccelUnitFromColumnName(std::string_view name);

// The accelerometer's name and datasheet unit of each Allan coefficient (table above), and the
// conversion from SI.
std::string_view AccelCoefficientName(estimators::Coefficient c);
std::string_view AccelDatasheetUnit(estimators::Coefficient c);
double AccelToDatasheetUnit(estimators::Coefficient c, double value_si);

}  // namespace allanlab::app
