#pragma once
// The rate units a user may ask for at the file edge (inside allanlab everything is rad/s).
#include <span>
#include <string>
#include <string_view>

namespace allanlab::app {

enum class RateUnit { kDegPerSecond, kDegPerHour, kRadPerSecond };

// Accepts exactly "deg/s", "deg/h" or "rad/s"; anything else is false with a message listing them.
bool ParseRateUnit(std::string_view text, RateUnit* unit, std::string* why);

// "deg/s", "deg/h", "rad/s": the spelling ParseRateUnit accepts, for messages and provenance.
std::string_view RateUnitName(RateUnit unit);

// "deg_per_s", "deg_per_h", "rad_per_s": for column and key names, where '/' is awkward.
std::string_view RateUnitIdentifier(RateUnit unit);

// A rate in rad/s expressed in `unit` (the same arithmetic as sim/units.h, so values agree to the
// last bit with every other place that prints deg/h).
double FromRadPerSecond(RateUnit unit, double rad_per_s);

// A rate given in `unit`, in rad/s (the inverse of FromRadPerSecond, same sim/units.h factors).
double ToRadPerSecond(RateUnit unit, double value);
// The same for every value in place (the unit chosen once: a vectorised loop).
void ToRadPerSecond(RateUnit unit, std::span<double> values);

}  // namespace allanlab::app
