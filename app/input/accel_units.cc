#include "app/input/accel_units.h"

#include <vector>

#include "app/input/stated_units.h"
#include "sim/units.h"

namespace allanlab::app {
namespace {

using estimators::Coefficient;

// The unit in a word sequence: m/s^2 as "m s 2", "mps2", "ms2", "m s2"; g; mg.
std::string AccelUnitOfTokens(const std::vector<std::string>& t) {
  if (t.size() == 1) {
    if (t[0] == "g") return "g";
    if (t[0] == "mg") return "mg";
    if (t[0] == "mps2" || t[0] == "ms2" || t[0] == "mpss") return "m/s^2";
  }
  if ((t.size() == 3 && t[0] == "m" && t[1] == "s" && t[2] == "2") ||
      (t.size() == 2 && t[0] == "m" && t[1] == "s2")) {
    return "m/s^2";
  }
  return "";
}

}  // namespace

bool ParseAccelUnit(std::string_view text, AccelUnit* unit, std::string* why) {
  // "m/s²": the superscript two (UTF-8 C2 B2) is a 2; "m s^-2": the minus belongs to the
  // exponent, not a separator.
  std::string s;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\xC2' && i + 1 < text.size() && text[i + 1] == '\xB2') {
      s += '2';
      ++i;
    } else if (!(text[i] == '-' && i + 1 < text.size() && text[i + 1] == '2')) {
      s += text[i];
    }
  }
  const std::string found = AccelUnitOfTokens(UnitTokens(s));
  for (AccelUnit candidate : {AccelUnit::kMeterPerSecond2, AccelUnit::kG, AccelUnit::kMilliG}) {
    if (found == AccelUnitName(candidate)) {
      *unit = candidate;
      return true;
    }
  }
  if (why) *why = "unknown accelerometer unit '" + std::string(text) + "' (expected m/s^2, g or mg)";
  return false;
}

std::string_view AccelUnitName(AccelUnit unit) {
  switch (unit) {
    case AccelUnit::kMeterPerSecond2:
      return "m/s^2";
    case AccelUnit::kG:
      return "g";
    case AccelUnit::kMilliG:
      return "mg";
  }
  return "?";
}

std::string_view AccelUnitIdentifier(AccelUnit unit) {
  return unit == AccelUnit::kMeterPerSecond2 ? "m_per_s2" : AccelUnitName(unit);
}

double AccelToSi(AccelUnit unit, double value) {
  switch (unit) {
    case AccelUnit::kMeterPerSecond2:
      return value;
    case AccelUnit::kG:
      return value * kStandardGravity;
    case AccelUnit::kMilliG:
      return value * (kStandardGravity * 1e-3);
  }
  return value;
}

void AccelToSi(AccelUnit unit, std::span<double> values) {
  if (unit == AccelUnit::kMeterPerSecond2) return;
  const double scale = AccelToSi(unit, 1.0);
  for (double& v : values) v *= scale;
}

double AccelFromSi(AccelUnit unit, double m_per_s2) {
  return unit == AccelUnit::kMeterPerSecond2 ? m_per_s2 : m_per_s2 / AccelToSi(unit, 1.0);
}

std::string AccelUnitFromColumnName(std::string_view name) {
  const std::vector<std::string> t = UnitTokens(name);
  for (std::size_t i = 0; i + 1 < t.size(); ++i) {
    // ROS sensor_msgs/Imu linear_acceleration is m/s^2 by definition (REP 103).
    if (t[i] == "linear" && t[i + 1] == "acceleration") return "m/s^2";
  }
  // The unit is the name's last words: "Accel_X_g", "az_m_s2", "acc_x [m/s^2]", "ax_mg".
  for (std::size_t words = 1; words <= 3 && words < t.size(); ++words) {
    const std::string unit =
        AccelUnitOfTokens(std::vector<std::string>(t.end() - static_cast<std::ptrdiff_t>(words), t.end()));
    if (!unit.empty()) return unit;
  }
  return "";
}

std::string_view AccelCoefficientName(Coefficient c) {
  switch (c) {
    case Coefficient::kQ:
      return "velocity quantization";
    case Coefficient::kN:
      return "velocity random walk (VRW)";
    case Coefficient::kB:
      return "bias instability";
    case Coefficient::kK:
      return "acceleration random walk";
    case Coefficient::kR:
      return "acceleration ramp";
  }
  return "?";
}

std::string_view AccelDatasheetUnit(Coefficient c) {
  switch (c) {
    case Coefficient::kQ:
      return "m/s";
    case Coefficient::kN:
      return "m/s/sqrt(h)";
    case Coefficient::kB:
      return "mg";
    case Coefficient::kK:
      return "m/s^2/sqrt(h)";
    case Coefficient::kR:
      return "m/s^2/h";
  }
  return "?";
}

double AccelToDatasheetUnit(Coefficient c, double v) {
  switch (c) {
    case Coefficient::kQ:
      return v;
    case Coefficient::kN:
      return v * units::kSqrtSecondsPerHour;
    case Coefficient::kB:
      return AccelFromSi(AccelUnit::kMilliG, v);
    case Coefficient::kK:
      return v * units::kSqrtSecondsPerHour;
    case Coefficient::kR:
      return v * units::kSecondsPerHour;
  }
  return v;
}

}  // namespace allanlab::app
