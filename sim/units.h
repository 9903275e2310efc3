#pragma once
// Unit conversions between the datasheet units of IEEE Std 952 and the SI units used inside
// allanlab (rad, s). Every coefficient inside the code is SI; conversion happens only at the
// edges (YAML specs, CLI options, printed tables).
#include <cmath>
#include <numbers>

namespace allanlab::units {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kRadPerDeg = kPi / 180.0;
inline constexpr double kSecondsPerHour = 3600.0;
inline constexpr double kSqrtSecondsPerHour = 60.0;  // sqrt(3600 s)
inline constexpr double kRadPerArcsec = kRadPerDeg / 3600.0;

// Rate: deg/h -> rad/s, deg/s -> rad/s.
constexpr double DegPerHour(double v) { return v * kRadPerDeg / kSecondsPerHour; }
constexpr double DegPerSecond(double v) { return v * kRadPerDeg; }
// Angle random walk N: deg/sqrt(h) -> rad/sqrt(s) (= rad/s/sqrt(Hz), the Kalibr noise density).
constexpr double DegPerSqrtHour(double v) { return v * kRadPerDeg / kSqrtSecondsPerHour; }
// Rate random walk K: deg/h/sqrt(h) -> rad/s/sqrt(s) (= rad/s^2/sqrt(Hz)).
constexpr double DegPerHourPerSqrtHour(double v) {
  return v * kRadPerDeg / (kSecondsPerHour * kSqrtSecondsPerHour);
}
// Rate ramp R: deg/h^2 -> rad/s^2.
constexpr double DegPerHourSquared(double v) {
  return v * kRadPerDeg / (kSecondsPerHour * kSecondsPerHour);
}
// Inverse conversions (SI -> datasheet units) for printing.
constexpr double ToDegPerHour(double rad_per_s) { return rad_per_s / DegPerHour(1.0); }
constexpr double ToDegPerSecond(double rad_per_s) { return rad_per_s / kRadPerDeg; }
constexpr double ToDegPerSqrtHour(double v) { return v / DegPerSqrtHour(1.0); }
constexpr double ToDegPerHourPerSqrtHour(double v) { return v / DegPerHourPerSqrtHour(1.0); }
constexpr double ToDegPerHourSquared(double v) { return v / DegPerHourSquared(1.0); }

// sqrt(2 ln2 / pi): ADEV floor of flicker rate noise per unit B (docs/theory.md §1.3, §1.5).
inline const double kFlickerFloorFactor = std::sqrt(2.0 * std::numbers::ln2 / kPi);

}  // namespace allanlab::units
