#include "sim/quantity.h"

#include <array>
#include <charconv>
#include <cmath>
#include <sstream>
#include <system_error>

#include "sim/units.h"

namespace allanlab::sim {
namespace {

// A unit reduced to a factor times rad^angle s^time. Units are parsed as products and quotients
// of atoms instead of being looked up in a fixed list, so every spelling datasheets use
// ("deg/h/sqrt(Hz)", "°/√h", "deg/h^1.5", "rad/s^2/sqrt(Hz)") reduces to the same thing and a
// unit of the wrong dimension can be named in the error message.
struct UnitValue {
  double factor = 1.0;
  double angle_exponent = 0.0;
  double time_exponent = 0.0;
};

UnitValue Multiply(const UnitValue& a, const UnitValue& b) {
  return {a.factor * b.factor, a.angle_exponent + b.angle_exponent,
          a.time_exponent + b.time_exponent};
}

UnitValue Power(const UnitValue& a, double e) {
  return {std::pow(a.factor, e), a.angle_exponent * e, a.time_exponent * e};
}

struct Atom {
  std::string_view name;
  UnitValue value;
};

constexpr double kDeg = units::kRadPerDeg;
constexpr double kHour = units::kSecondsPerHour;

// Case-sensitive on purpose: "mHz" and "MHz" differ by 10^9.
constexpr std::array<Atom, 21> kAtoms = {{
    {"rad", {1.0, 1, 0}},
    {"mrad", {1e-3, 1, 0}},
    {"urad", {1e-6, 1, 0}},
    {"deg", {kDeg, 1, 0}},
    {"arcmin", {kDeg / 60.0, 1, 0}},
    {"arcsec", {units::kRadPerArcsec, 1, 0}},
    {"s", {1.0, 0, 1}},
    {"sec", {1.0, 0, 1}},
    {"ms", {1e-3, 0, 1}},
    {"us", {1e-6, 0, 1}},
    {"min", {60.0, 0, 1}},
    {"h", {kHour, 0, 1}},
    {"hr", {kHour, 0, 1}},
    {"hour", {kHour, 0, 1}},
    {"Hz", {1.0, 0, -1}},
    {"kHz", {1e3, 0, -1}},
    {"mHz", {1e-3, 0, -1}},
    {"dps", {kDeg, 1, -1}},
    {"mdps", {1e-3 * kDeg, 1, -1}},
    {"dph", {kDeg / kHour, 1, -1}},
    {"rpm", {2.0 * units::kPi / 60.0, 1, -1}},
}};

// Non-ASCII symbols, as UTF-8.
constexpr std::string_view kDegreeSign = "\xC2\xB0";       // °
constexpr std::string_view kMicroSign = "\xC2\xB5";        // µ
constexpr std::string_view kGreekMu = "\xCE\xBC";          // μ
constexpr std::string_view kSquareRoot = "\xE2\x88\x9A";   // √
constexpr std::string_view kDoublePrime = "\xE2\x80\xB3";  // ″ (arcsec)
constexpr std::string_view kPrime = "\xE2\x80\xB2";        // ′ (arcmin)
constexpr std::string_view kSuperscript2 = "\xC2\xB2";     // ²
constexpr std::string_view kSuperscript3 = "\xC2\xB3";     // ³
constexpr std::string_view kMiddleDot = "\xC2\xB7";        // ·

// Recursive descent over
//   product := power (('/' | '*' | '·') power)*          left-associative: deg/h/h = deg h^-2
//   power   := factor ('^' exponent | '²' | '³')?
//   factor  := '(' product ')' | ('sqrt' | 'rt' | '√') ['-'] factor | atom
class UnitParser {
 public:
  explicit UnitParser(std::string_view text) : text_(text) {}

  bool Parse(UnitValue* out, std::string* error) {
    const bool ok = ParseProduct(out) && AtEnd();
    if (!ok)
      *error = error_.empty() ? "unexpected \"" + std::string(text_.substr(pos_)) + "\"" : error_;
    return ok;
  }

 private:
  bool AtEnd() {
    SkipSpace();
    return pos_ == text_.size();
  }
  void SkipSpace() {
    while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\t')) ++pos_;
  }
  bool Consume(std::string_view token) {
    SkipSpace();
    if (text_.substr(pos_, token.size()) != token) return false;
    pos_ += token.size();
    return true;
  }
  bool Fail(std::string message) {
    if (error_.empty()) error_ = std::move(message);
    return false;
  }

  bool ParseProduct(UnitValue* out) {
    if (!ParsePower(out)) return false;
    while (true) {
      bool divide = false;
      if (Consume("/")) {
        divide = true;
      } else if (!Consume("*") && !Consume(kMiddleDot)) {
        return true;
      }
      UnitValue rhs;
      if (!ParsePower(&rhs)) return false;
      *out = Multiply(*out, divide ? Power(rhs, -1.0) : rhs);
    }
  }

  bool ParsePower(UnitValue* out) {
    if (!ParseFactor(out)) return false;
    double exponent = 1.0;
    if (Consume("^")) {
      if (!ParseExponent(&exponent)) return false;
    } else if (Consume(kSuperscript2)) {
      exponent = 2.0;
    } else if (Consume(kSuperscript3)) {
      exponent = 3.0;
    }
    *out = Power(*out, exponent);
    return true;
  }

  // "2", "-1", "1.5", "(3/2)".
  bool ParseExponent(double* out) {
    const bool parenthesised = Consume("(");
    if (!ParseNumber(out)) return Fail("exponent must be a number");
    if (parenthesised) {
      if (Consume("/")) {
        double denominator = 0.0;
        if (!ParseNumber(&denominator) || denominator == 0.0) {
          return Fail("exponent denominator must be a non-zero number");
        }
        *out /= denominator;
      }
      if (!Consume(")")) return Fail("missing \")\" in exponent");
    }
    return true;
  }

  bool ParseNumber(double* out) {
    SkipSpace();
    const char* first = text_.data() + pos_;
    const char* last = text_.data() + text_.size();
    const auto [end, ec] = std::from_chars(first, last, *out);
    if (ec != std::errc() || !std::isfinite(*out)) return false;
    pos_ += static_cast<std::size_t>(end - first);
    return true;
  }

  bool ParseFactor(UnitValue* out) {
    SkipSpace();
    if (Consume("(")) {
      if (!ParseProduct(out)) return false;
      if (!Consume(")")) return Fail("missing \")\"");
      return true;
    }
    if (Consume(kSquareRoot)) return ParseRoot(out);
    if (Consume(kDegreeSign)) return Found({kDeg, 1, 0}, out);
    if (Consume(kDoublePrime)) return Found({units::kRadPerArcsec, 1, 0}, out);
    if (Consume(kPrime)) return Found({kDeg / 60.0, 1, 0}, out);
    const std::string name = ReadIdentifier();
    if (name.empty()) {
      return Fail(pos_ < text_.size() ? "unexpected \"" + std::string(text_.substr(pos_)) + "\""
                                      : "unit ends early");
    }
    if (name == "sqrt" || name == "rt") {
      Consume("-");  // "deg/rt-hr"
      return ParseRoot(out);
    }
    for (const Atom& atom : kAtoms) {
      if (atom.name == name) return Found(atom.value, out);
    }
    return Fail("unknown unit \"" + name + "\"");
  }

  bool ParseRoot(UnitValue* out) {
    if (!ParseFactor(out)) return false;
    *out = Power(*out, 0.5);
    return true;
  }

  static bool Found(const UnitValue& value, UnitValue* out) {
    *out = value;
    return true;
  }

  // ASCII letters; the micro sign and Greek mu read as 'u' so "µrad" and "μrad" are "urad".
  std::string ReadIdentifier() {
    std::string name;
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z')) {
        name += c;
        ++pos_;
      } else if (text_.substr(pos_, 2) == kMicroSign || text_.substr(pos_, 2) == kGreekMu) {
        name += 'u';
        pos_ += 2;
      } else {
        break;
      }
    }
    return name;
  }

  std::string_view text_;
  std::size_t pos_ = 0;
  std::string error_;
};

struct DimensionInfo {
  Dimension dimension;
  std::string_view name;
  std::string_view si_unit;
  double angle_exponent;
  double time_exponent;
  std::string_view accepted;
};

constexpr std::array<DimensionInfo, 7> kDimensions = {{
    {Dimension::kRate, "rate", "rad/s", 1, -1,
     "rad/s, mrad/s, urad/s, deg/s (dps, \xC2\xB0/s), deg/h (dph, \xC2\xB0/h)"},
    {Dimension::kArw, "angle random walk", "rad/sqrt(s)", 1, -0.5,
     "deg/sqrt(h) (deg/rt(h), \xC2\xB0/\xE2\x88\x9Ah), deg/h/sqrt(Hz), deg/s/sqrt(Hz), "
     "rad/s/sqrt(Hz), rad/sqrt(s)"},
    {Dimension::kRrw, "rate random walk", "rad/s/sqrt(s)", 1, -1.5,
     "deg/h/sqrt(h) (deg/h^1.5), rad/s^2/sqrt(Hz), rad/s/sqrt(s)"},
    {Dimension::kRamp, "rate ramp", "rad/s^2", 1, -2, "deg/h^2 (deg/h/h), deg/s^2, rad/s^2"},
    {Dimension::kAngle, "angle", "rad", 1, 0,
     "rad, mrad, urad (\xC2\xB5rad), deg (\xC2\xB0), arcmin, arcsec"},
    {Dimension::kTime, "time", "s", 0, 1, "s, ms, us, min, h"},
    {Dimension::kFrequency, "frequency", "Hz", 0, -1, "Hz, kHz, mHz"},
}};

const DimensionInfo& Info(Dimension dimension) {
  for (const DimensionInfo& info : kDimensions) {
    if (info.dimension == dimension) return info;
  }
  return kDimensions[0];  // unreachable: every enumerator is in the table
}

bool SameExponent(double a, double b) { return std::abs(a - b) < 1e-9; }

// "a rate", "an angle".
std::string WithArticle(std::string_view name) {
  return std::string(name.front() == 'a' ? "an " : "a ") + std::string(name);
}

// "a rate", or "rad^1 s^-0.5" when the unit is none of ours.
std::string DescribeDimension(const UnitValue& unit) {
  for (const DimensionInfo& info : kDimensions) {
    if (SameExponent(unit.angle_exponent, info.angle_exponent) &&
        SameExponent(unit.time_exponent, info.time_exponent)) {
      return WithArticle(info.name);
    }
  }
  std::ostringstream os;
  os << "rad^" << unit.angle_exponent << " s^" << unit.time_exponent;
  return os.str();
}

std::string_view Trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

}  // namespace

bool ParseQuantity(std::string_view text, Dimension dimension, double* si_value, std::string* why) {
  const DimensionInfo& info = Info(dimension);
  auto fail = [&](const std::string& problem) {
    if (why) {
      // A stream rather than operator+ chains: GCC 12 -O2 gives a false -Wrestrict on those.
      std::ostringstream os;
      os << '"' << text << "\": " << problem << "; " << WithArticle(info.name) << " takes one of "
         << info.accepted;
      *why = os.str();
    }
    return false;
  };
  std::string_view rest = Trim(text);
  if (rest.empty()) return fail("empty");
  if (rest.front() == '+') rest.remove_prefix(1);
  double number = 0.0;
  const auto [end, ec] = std::from_chars(rest.data(), rest.data() + rest.size(), number);
  if (ec == std::errc::result_out_of_range) return fail("number out of range");
  if (ec != std::errc()) return fail("does not start with a number");
  if (!std::isfinite(number)) return fail("the number must be finite");
  const std::string_view unit_text = Trim(rest.substr(static_cast<std::size_t>(end - rest.data())));
  if (unit_text.empty()) return fail("missing unit (the unit is part of the value)");

  UnitValue unit;
  std::string unit_error;
  if (!UnitParser(unit_text).Parse(&unit, &unit_error)) return fail(unit_error);
  if (!SameExponent(unit.angle_exponent, info.angle_exponent) ||
      !SameExponent(unit.time_exponent, info.time_exponent)) {
    return fail(std::string(unit_text) + " is " + DescribeDimension(unit) + ", not " +
                WithArticle(info.name));
  }
  const double value = number * unit.factor;
  if (!std::isfinite(value)) return fail("value out of range");
  *si_value = value;
  return true;
}

std::string_view SiUnitName(Dimension dimension) { return Info(dimension).si_unit; }

}  // namespace allanlab::sim
