#pragma once
// What a record says about the units of its samples, and how that meets --units.
//
// A record may state its units in three places: the value column's name (`rate_rad_per_s`,
// `Gyro_X_dps`, `gyro_x_rad_s`, `wz [deg/h]`, `field.angular_velocity.x` of a ROS sensor_msgs/Imu,
// which is rad/s by definition), a `# units: deg/s` comment line before the first data row (what
// `allanlab simulate` writes), and the JSON sidecar of a raw record (`"units"`). Every statement
// must agree with every other and with --units; a disagreement is an error naming both, never a
// silent choice. When neither the file nor the command line states the units, the record is
// refused: a gyro rate read in the wrong unit is off by 57x (rad/s vs deg/s) or 3600x (deg/s vs
// deg/h) without any other sign of trouble, so no unit is assumed.
//
// Units: rate deg/s, deg/h, rad/s; angle (the integrated rate) deg, rad, arcsec.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "estimators/avar_summary.h"

namespace allanlab::app {

// The lower-case alphanumeric words of a unit or column name ("Gyro_X [°/s]" -> gyro, x, deg, s;
// the degree sign is the word "deg"), as the unit readers here and in app/input/accel_units.h see them.
std::vector<std::string> UnitTokens(std::string_view text);

// One statement of the units: the canonical spelling ("deg/s", "rad", ...) and where it was read,
// for messages ("column rate_rad_per_s", "the '# units:' line", "sidecar r.f64.json", "--units").
struct StatedUnit {
  std::string unit;
  std::string source;
};

// The units named by a column header, if any. Fails (false, *why set) when the name states a unit
// allanlab does not read (mdps, mrad/s, rad/h, ...) or a rate unit for angle samples; true with
// *unit empty when the name says nothing about units.
bool UnitFromColumnName(std::string_view name, estimators::InputKind kind,
                        std::optional<StatedUnit>* unit, std::string* why);

// The canonical spelling of a unit written as text (a `# units:` value, a sidecar's "units", the
// --units option): "deg/s", "deg/h", "rad/s" for rate; "deg", "rad", "arcsec" for angle. Also
// reads "°/s", "dps", "rad/sec", "deg/hr", "degrees", case-insensitively. False with the choices
// in *why otherwise.
bool CanonicalUnit(std::string_view text, estimators::InputKind kind, std::string* unit,
                   std::string* why);

// Every statement (file first, --units last) reduced to one unit. Fails when two disagree ("--units
// deg/s contradicts column rate_rad_per_s (rad/s)") or when there is none (the message says how to
// state it). `what` names the samples for that message ("column Gyro_X").
bool ResolveUnits(const std::vector<StatedUnit>& stated, estimators::InputKind kind,
                  const std::string& what, StatedUnit* resolved, std::string* why);

}  // namespace allanlab::app
