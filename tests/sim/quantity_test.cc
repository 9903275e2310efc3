// Every accepted unit of every dimension against an SI value worked out by hand from the unit's
// definition (not from sim/units.h, so a wrong constant there would show up here), and the
// inputs that must be rejected.
#include "sim/quantity.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

namespace allanlab::sim {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;  // rad per degree

struct Case {
  const char* text;
  double si;
};

void ExpectParses(Dimension dimension, const Case& c) {
  double value = 0.0;
  std::string why;
  ASSERT_TRUE(ParseQuantity(c.text, dimension, &value, &why)) << c.text << ": " << why;
  EXPECT_NEAR(value, c.si, 1e-12 * std::abs(c.si))
      << c.text << " -> " << value << " " << SiUnitName(dimension) << ", expected " << c.si;
}

void ExpectRejected(const char* text, Dimension dimension, const std::string& fragment) {
  double value = 123.0;
  std::string why;
  EXPECT_FALSE(ParseQuantity(text, dimension, &value, &why)) << text << " was accepted";
  EXPECT_NE(why.find(fragment), std::string::npos)
      << "message for \"" << text << "\" lacks \"" << fragment << "\": " << why;
  EXPECT_EQ(value, 123.0) << "output written on failure for " << text;
}

TEST(ParseQuantity, Rate) {
  for (const Case& c : {Case{"1 rad/s", 1.0}, Case{"2 mrad/s", 2e-3}, Case{"3 urad/s", 3e-6},
                        Case{"3 \xC2\xB5rad/s", 3e-6}, Case{"1 deg/s", kDeg}, Case{"1 dps", kDeg},
                        Case{"1 \xC2\xB0/s", kDeg}, Case{"3600 deg/h", kDeg},
                        Case{"3600 deg/hr", kDeg}, Case{"3600 dph", kDeg},
                        Case{"3600 \xC2\xB0/h", kDeg}, Case{"0.12 deg/h", 0.12 * kDeg / 3600.0},
                        Case{"-0.5 deg/s", -0.5 * kDeg}, Case{"60 rpm", 2.0 * std::numbers::pi}}) {
    ExpectParses(Dimension::kRate, c);
  }
}

TEST(ParseQuantity, AngleRandomWalk) {
  // 1 deg/sqrt(h) = (pi/180) rad / sqrt(3600 s) = pi/180/60 rad/sqrt(s).
  const double deg_per_sqrt_h = kDeg / 60.0;
  for (const Case& c :
       {Case{"1 deg/sqrt(h)", deg_per_sqrt_h}, Case{"1 deg/rt(h)", deg_per_sqrt_h},
        Case{"1 deg/sqrt(hr)", deg_per_sqrt_h}, Case{"1 deg/rt-hr", deg_per_sqrt_h},
        Case{"1 deg/\xE2\x88\x9Ah", deg_per_sqrt_h},       // deg/√h
        Case{"1 \xC2\xB0/\xE2\x88\x9Ah", deg_per_sqrt_h},  // °/√h
        Case{"1 deg / sqrt( h )", deg_per_sqrt_h}, Case{"1 deg/h^0.5", deg_per_sqrt_h},
        // deg/h/sqrt(Hz) = (pi/180/3600) rad/s * sqrt(s): 60 of them are 1 deg/sqrt(h).
        Case{"60 deg/h/sqrt(Hz)", deg_per_sqrt_h}, Case{"1 deg/h/sqrt(Hz)", kDeg / 3600.0},
        Case{"1 deg/s/sqrt(Hz)", kDeg}, Case{"0.005 deg/s/sqrt(Hz)", 0.3 * deg_per_sqrt_h},
        Case{"1 dps/\xE2\x88\x9AHz", kDeg}, Case{"1 rad/s/sqrt(Hz)", 1.0},
        Case{"1 rad/sqrt(s)", 1.0}, Case{"0.0267 deg/sqrt(h)", 0.0267 * deg_per_sqrt_h}}) {
    ExpectParses(Dimension::kArw, c);
  }
}

TEST(ParseQuantity, RateRandomWalk) {
  // 1 deg/h/sqrt(h) = (pi/180) rad / (3600 s * 60 sqrt(s)).
  const double deg_per_h_per_sqrt_h = kDeg / (3600.0 * 60.0);
  for (const Case& c :
       {Case{"1 deg/h/sqrt(h)", deg_per_h_per_sqrt_h}, Case{"1 deg/h/rt(h)", deg_per_h_per_sqrt_h},
        Case{"1 deg/h^1.5", deg_per_h_per_sqrt_h}, Case{"1 deg/h^(3/2)", deg_per_h_per_sqrt_h},
        Case{"1 \xC2\xB0/h/\xE2\x88\x9Ah", deg_per_h_per_sqrt_h}, Case{"1 rad/s^2/sqrt(Hz)", 1.0},
        Case{"1 rad/s\xC2\xB2/\xE2\x88\x9AHz", 1.0},  // rad/s²/√Hz
        Case{"1 rad/s/sqrt(s)", 1.0}}) {
    ExpectParses(Dimension::kRrw, c);
  }
}

TEST(ParseQuantity, RateRamp) {
  const double deg_per_h2 = kDeg / (3600.0 * 3600.0);
  for (const Case& c : {Case{"1 deg/h^2", deg_per_h2}, Case{"1 deg/h/h", deg_per_h2},
                        Case{"1 deg/h\xC2\xB2", deg_per_h2}, Case{"1 deg/s^2", kDeg},
                        Case{"1 rad/s^2", 1.0}, Case{"-2 deg/h^2", -2.0 * deg_per_h2}}) {
    ExpectParses(Dimension::kRamp, c);
  }
}

TEST(ParseQuantity, Angle) {
  for (const Case& c :
       {Case{"1 rad", 1.0}, Case{"1 mrad", 1e-3}, Case{"0.5 urad", 0.5e-6},
        Case{"0.5 \xC2\xB5rad", 0.5e-6},  // micro sign
        Case{"0.5 \xCE\xBCrad", 0.5e-6},  // Greek mu
        Case{"1 deg", kDeg}, Case{"1 \xC2\xB0", kDeg}, Case{"1 arcmin", kDeg / 60.0},
        Case{"1 arcsec", kDeg / 3600.0}, Case{"0.3 arcsec", 0.3 * kDeg / 3600.0}}) {
    ExpectParses(Dimension::kAngle, c);
  }
}

TEST(ParseQuantity, Time) {
  for (const Case& c : {Case{"1 s", 1.0}, Case{"2 sec", 2.0}, Case{"1 ms", 1e-3},
                        Case{"1 us", 1e-6}, Case{"1 \xC2\xB5s", 1e-6}, Case{"1 min", 60.0},
                        Case{"1 h", 3600.0}, Case{"1 hr", 3600.0}, Case{"0.5 hour", 1800.0}}) {
    ExpectParses(Dimension::kTime, c);
  }
}

TEST(ParseQuantity, Frequency) {
  for (const Case& c : {Case{"100 Hz", 100.0}, Case{"100Hz", 100.0}, Case{"  100 Hz  ", 100.0},
                        Case{"+100 Hz", 100.0}, Case{"1e2 Hz", 100.0}, Case{"2 kHz", 2000.0},
                        Case{"10 mHz", 0.01}}) {
    ExpectParses(Dimension::kFrequency, c);
  }
}

TEST(ParseQuantity, RejectsBareNumberAndNamesTheAcceptedUnits) {
  ExpectRejected("0.0267", Dimension::kArw, "missing unit");
  ExpectRejected("0.0267", Dimension::kArw, "deg/sqrt(h)");
  ExpectRejected("100", Dimension::kFrequency, "Hz, kHz");
  ExpectRejected("1", Dimension::kAngle, "arcsec");
}

TEST(ParseQuantity, RejectsNonFiniteNumbers) {
  ExpectRejected("nan deg/h", Dimension::kRate, "finite");
  ExpectRejected("inf deg/h", Dimension::kRate, "finite");
  ExpectRejected("-inf Hz", Dimension::kFrequency, "finite");
  ExpectRejected("1e400 Hz", Dimension::kFrequency, "out of range");
}

TEST(ParseQuantity, RejectsUnitOfTheWrongDimension) {
  ExpectRejected("0.1 deg/h", Dimension::kArw, "deg/h is a rate, not an angle random walk");
  ExpectRejected("0.1 deg/h/sqrt(h)", Dimension::kArw, "is a rate random walk");
  ExpectRejected("0.1 deg/h/sqrt(Hz)", Dimension::kRrw, "is an angle random walk");
  ExpectRejected("1 Hz", Dimension::kTime, "is a frequency, not a time");
  ExpectRejected("1 rad/s", Dimension::kFrequency, "not a frequency");
  ExpectRejected("1 deg*s", Dimension::kRate, "rad^1 s^1");
  // The message lists what would have been accepted.
  ExpectRejected("0.1 deg/h", Dimension::kArw, "deg/h/sqrt(Hz)");
}

TEST(ParseQuantity, RejectsMalformedText) {
  ExpectRejected("", Dimension::kRate, "empty");
  ExpectRejected("deg/h", Dimension::kRate, "does not start with a number");
  ExpectRejected("1 furlong/h", Dimension::kRate, "unknown unit \"furlong\"");
  ExpectRejected("1 MHz", Dimension::kFrequency, "unknown unit \"MHz\"");  // case-sensitive
  ExpectRejected("1 hz", Dimension::kFrequency, "unknown unit \"hz\"");
  ExpectRejected("1 deg/sqrt(h", Dimension::kArw, "missing \")\"");
  ExpectRejected("1 deg/h^x", Dimension::kRamp, "exponent");
  ExpectRejected("1 deg/", Dimension::kRate, "unit ends early");
  ExpectRejected("1 deg h", Dimension::kRate, "unexpected");
}

TEST(ParseQuantity, WhyMayBeNull) {
  double value = 0.0;
  EXPECT_FALSE(ParseQuantity("1", Dimension::kRate, &value, nullptr));
  EXPECT_TRUE(ParseQuantity("1 rad/s", Dimension::kRate, &value, nullptr));
  EXPECT_EQ(value, 1.0);
}

TEST(SiUnitName, NamesEachDimension) {
  EXPECT_EQ(SiUnitName(Dimension::kRate), "rad/s");
  EXPECT_EQ(SiUnitName(Dimension::kArw), "rad/sqrt(s)");
  EXPECT_EQ(SiUnitName(Dimension::kRrw), "rad/s/sqrt(s)");
  EXPECT_EQ(SiUnitName(Dimension::kRamp), "rad/s^2");
  EXPECT_EQ(SiUnitName(Dimension::kAngle), "rad");
  EXPECT_EQ(SiUnitName(Dimension::kTime), "s");
  EXPECT_EQ(SiUnitName(Dimension::kFrequency), "Hz");
}

}  // namespace
}  // namespace allanlab::sim
