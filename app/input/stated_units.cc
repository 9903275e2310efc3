#include "app/input/stated_units.h"

#include <array>
#include <utility>

namespace allanlab::app {
namespace {

using estimators::InputKind;

char Lower(char c) { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c; }
bool IsAlnum(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
}

bool OneOf(const std::string& token, std::initializer_list<std::string_view> words) {
  for (std::string_view w : words) {
    if (token == w) return true;
  }
  return false;
}

bool IsDeg(const std::string& t) { return OneOf(t, {"deg", "degree", "degrees"}); }
bool IsRad(const std::string& t) { return OneOf(t, {"rad", "radian", "radians"}); }
bool IsSecond(const std::string& t) { return OneOf(t, {"s", "sec", "second", "seconds"}); }
bool IsHour(const std::string& t) { return OneOf(t, {"h", "hr", "hour", "hours"}); }
// Scaled angles that no --units spelling covers (milli-degree/s of many MEMS data sheets).
bool IsScaledAngle(const std::string& t) {
  return OneOf(t, {"mdeg", "mrad", "urad", "udeg", "mdps", "mradps"});
}

// What a token sequence says about a rate unit starting at `i`: "deg/s", "deg/h", "rad/s", a
// non-empty unsupported spelling in *unsupported, or nothing. *length: tokens consumed.
std::string RateAt(const std::vector<std::string>& t, std::size_t i, std::size_t* length,
                   std::string* unsupported) {
  const std::string& a = t[i];
  if (OneOf(a, {"dps", "degps", "degpersec"})) return *length = 1, "deg/s";
  if (OneOf(a, {"dph", "degph", "degperhour"})) return *length = 1, "deg/h";
  if (OneOf(a, {"radps", "radpersec"})) return *length = 1, "rad/s";
  if (OneOf(a, {"mdps", "mradps"})) {
    *unsupported = a;
    return *length = 1, "";
  }
  const bool deg = IsDeg(a), rad = IsRad(a), scaled = IsScaledAngle(a);
  if (!deg && !rad && !scaled) return "";
  std::size_t j = i + 1;
  if (j < t.size() && t[j] == "per") ++j;
  if (j >= t.size()) return "";
  const bool second = IsSecond(t[j]), hour = IsHour(t[j]);
  if (!second && !hour) return "";
  *length = j + 1 - i;
  if (scaled || (rad && hour)) {
    *unsupported = a + "/" + t[j];
    return "";
  }
  return deg ? (second ? "deg/s" : "deg/h") : "rad/s";
}

std::string AngleOf(const std::string& t) {
  if (IsDeg(t)) return "deg";
  if (IsRad(t)) return "rad";
  if (OneOf(t, {"arcsec", "asec"})) return "arcsec";
  return "";
}

std::string Choices(InputKind kind) {
  return kind == InputKind::kRate ? "deg/s, deg/h or rad/s" : "deg, rad or arcsec";
}

}  // namespace

// Lower-case alphanumeric tokens; the degree sign (UTF-8 C2 B0) is the token "deg".
std::vector<std::string> UnitTokens(std::string_view text) {
  std::vector<std::string> out;
  std::string current;
  const auto flush = [&] {
    if (!current.empty()) out.push_back(std::move(current));
    current.clear();
  };
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\xC2' && i + 1 < text.size() && text[i + 1] == '\xB0') {
      flush();
      out.emplace_back("deg");
      ++i;
    } else if (IsAlnum(text[i])) {
      current += Lower(text[i]);
    } else {
      flush();
    }
  }
  flush();
  return out;
}

bool UnitFromColumnName(std::string_view name, InputKind kind, std::optional<StatedUnit>* unit,
                        std::string* why) {
  unit->reset();
  const std::vector<std::string> t = UnitTokens(name);
  const std::string source = "column " + std::string(name);
  // A ROS sensor_msgs/Imu angular_velocity is rad/s by definition (REP 103), whatever the export
  // tool called the column (`field.angular_velocity.x`, `angular_velocity_x`).
  for (std::size_t i = 0; i + 1 < t.size(); ++i) {
    if (t[i] == "angular" && t[i + 1] == "velocity") {
      if (kind == InputKind::kAngle) {
        *why = source + " holds angular velocity (rad/s), not an angle: drop --type angle";
        return false;
      }
      *unit = StatedUnit{"rad/s", source + " (ROS angular_velocity)"};
      return true;
    }
  }
  for (std::size_t i = 0; i < t.size(); ++i) {
    std::size_t length = 0;
    std::string unsupported;
    const std::string rate = RateAt(t, i, &length, &unsupported);
    if (!unsupported.empty()) {
      *why = source + " states " + unsupported + ", a unit allanlab does not convert (" +
             Choices(InputKind::kRate) + "): convert the column first";
      return false;
    }
    if (rate.empty()) continue;
    if (kind == InputKind::kAngle) {
      *why = source + " holds a rate (" + rate + "), not an angle: drop --type angle";
      return false;
    }
    *unit = StatedUnit{rate, source};
    return true;
  }
  // An angle unit counts only as the name's last word: "deg" elsewhere may be anything.
  if (kind == InputKind::kAngle && !t.empty()) {
    if (IsScaledAngle(t.back())) {
      *why = source + " states " + t.back() + ", a unit allanlab does not convert (" +
             Choices(kind) + "): convert the column first";
      return false;
    }
    if (const std::string angle = AngleOf(t.back()); !angle.empty()) {
      *unit = StatedUnit{angle, source};
    }
  }
  return true;
}

bool CanonicalUnit(std::string_view text, InputKind kind, std::string* unit, std::string* why) {
  const std::vector<std::string> t = UnitTokens(text);
  std::string found;
  if (kind == InputKind::kRate) {
    std::size_t length = 0;
    std::string unsupported;
    if (!t.empty()) found = RateAt(t, 0, &length, &unsupported);
    if (length != t.size()) found.clear();
  } else if (t.size() == 1) {
    found = AngleOf(t[0]);
  }
  if (found.empty()) {
    *why = "unknown " + std::string(kind == InputKind::kRate ? "rate" : "angle") + " unit '" +
           std::string(text) + "' (expected " + Choices(kind) + ")";
    return false;
  }
  *unit = found;
  return true;
}

bool ResolveUnits(const std::vector<StatedUnit>& stated, InputKind kind, const std::string& what,
                  StatedUnit* resolved, std::string* why) {
  if (stated.empty()) {
    *why = "the units of " + what + " are not stated in the file (a unit in the column name such " +
           "as _dps or _rad_s, or a '# units:' line): give --units " + Choices(kind);
    return false;
  }
  for (std::size_t i = 1; i < stated.size(); ++i) {
    if (stated[i].unit != stated[0].unit) {
      *why = stated[i].source + " (" + stated[i].unit + ") contradicts " + stated[0].source +
             " (" + stated[0].unit + ")" +
             (stated[i].source == "--units" ? ": drop --units or correct it" : "");
      return false;
    }
  }
  *resolved = stated[0];
  return true;
}

}  // namespace allanlab::app
