#include "app/input/rate_units.h"

#include "sim/units.h"

namespace allanlab::app {

bool ParseRateUnit(std::string_view text, RateUnit* unit, std::string* why) {
  for (RateUnit candidate :
       {RateUnit::kDegPerSecond, RateUnit::kDegPerHour, RateUnit::kRadPerSecond}) {
    if (text == RateUnitName(candidate)) {
      *unit = candidate;
      return true;
    }
  }
  if (why) *why = "unknown rate unit '" + std::string(text) + "' (expected deg/s, deg/h or rad/s)";
  return false;
}

std::string_view RateUnitName(RateUnit unit) {
  switch (unit) {
    case RateUnit::kDegPerSecond:
      return "deg/s";
    case RateUnit::kDegPerHour:
      return "deg/h";
    case RateUnit::kRadPerSecond:
      return "rad/s";
  }
  return "?";
}

std::string_view RateUnitIdentifier(RateUnit unit) {
  switch (unit) {
    case RateUnit::kDegPerSecond:
      return "deg_per_s";
    case RateUnit::kDegPerHour:
      return "deg_per_h";
    case RateUnit::kRadPerSecond:
      return "rad_per_s";
  }
  return "?";
}

double FromRadPerSecond(RateUnit unit, double rad_per_s) {
  switch (unit) {
    case RateUnit::kDegPerSecond:
      return units::ToDegPerSecond(rad_per_s);
    case RateUnit::kDegPerHour:
      return units::ToDegPerHour(rad_per_s);
    case RateUnit::kRadPerSecond:
      return rad_per_s;
  }
  return rad_per_s;
}

double ToRadPerSecond(RateUnit unit, double value) {
  switch (unit) {
    case RateUnit::kDegPerSecond:
      return units::DegPerSecond(value);
    case RateUnit::kDegPerHour:
      return units::DegPerHour(value);
    case RateUnit::kRadPerSecond:
      return value;
  }
  return value;
}

void ToRadPerSecond(RateUnit unit, std::span<double> values) {
  switch (unit) {
    case RateUnit::kDegPerSecond:
      for (double& v : values) v = units::DegPerSecond(v);
      return;
    case RateUnit::kDegPerHour:
      for (double& v : values) v = units::DegPerHour(v);
      return;
    case RateUnit::kRadPerSecond:
      return;
  }
}

}  // namespace allanlab::app
