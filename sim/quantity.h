#pragma once
// Physical quantities written by people ("0.0267 deg/sqrt(h)", "100 Hz") parsed into the SI value
// allanlab uses inside (rad, s). Used by the YAML sensor specs and the CLI.
#include <string>
#include <string_view>

namespace allanlab::sim {

enum class Dimension {
  kRate,       // rad/s       accepts rad/s, deg/s, deg/h, mrad/s, urad/s
  kArw,        // rad/sqrt(s) accepts deg/sqrt(h), deg/h/sqrt(Hz), deg/s/sqrt(Hz), rad/s/sqrt(Hz), rad/sqrt(s)
  kRrw,        // rad/s/sqrt(s) accepts deg/h/sqrt(h), deg/h^1.5, rad/s^2/sqrt(Hz), rad/s/sqrt(s)
  kRamp,       // rad/s^2     accepts deg/h^2, deg/h/h, deg/s^2, rad/s^2
  kAngle,      // rad         accepts rad, mrad, urad, deg, arcsec
  kTime,       // s           accepts s, ms, us, min, h
  kFrequency,  // Hz          accepts Hz, kHz
};

// Parses "<number> <unit>" (whitespace optional; unit spellings as listed, case-sensitive, with
// "sqrt(h)"/"rt(h)"/"√h" variants). A bare number without unit is rejected for every dimension:
// the unit is part of the value. Returns false with a message naming the accepted units.
bool ParseQuantity(std::string_view text, Dimension dimension, double* si_value, std::string* why);

// Human name of a dimension's SI unit, e.g. "rad/sqrt(s)".
std::string_view SiUnitName(Dimension dimension);

}  // namespace allanlab::sim
