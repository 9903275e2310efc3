#include "estimators/fit/noise_coefficient.h"

#include <cmath>
#include <numbers>

#include "sim/units.h"

namespace allanlab::estimators {

std::string_view CoefficientId(Coefficient c) {
  switch (c) {
    case Coefficient::kQ: return "Q";
    case Coefficient::kN: return "N";
    case Coefficient::kB: return "B";
    case Coefficient::kK: return "K";
    case Coefficient::kR: return "R";
  }
  return "?";
}

bool ParseCoefficient(std::string_view id, Coefficient* c) {
  for (Coefficient candidate : kAllCoefficients) {
    if (CoefficientId(candidate) == id) {
      *c = candidate;
      return true;
    }
  }
  return false;
}

std::string_view DatasheetUnit(Coefficient c) {
  switch (c) {
    case Coefficient::kQ: return "urad";
    case Coefficient::kN: return "deg/sqrt(h)";
    case Coefficient::kB: return "deg/h";
    case Coefficient::kK: return "deg/h/sqrt(h)";
    case Coefficient::kR: return "deg/h^2";
  }
  return "?";
}

double ToDatasheetUnit(Coefficient c, double v) {
  switch (c) {
    case Coefficient::kQ: return v * 1e6;
    case Coefficient::kN: return units::ToDegPerSqrtHour(v);
    case Coefficient::kB: return units::ToDegPerHour(v);
    case Coefficient::kK: return units::ToDegPerHourPerSqrtHour(v);
    case Coefficient::kR: return units::ToDegPerHourSquared(v);
  }
  return v;
}

double FromDatasheetUnit(Coefficient c, double v) {
  switch (c) {
    case Coefficient::kQ: return v * 1e-6;
    case Coefficient::kN: return units::DegPerSqrtHour(v);
    case Coefficient::kB: return units::DegPerHour(v);
    case Coefficient::kK: return units::DegPerHourPerSqrtHour(v);
    case Coefficient::kR: return units::DegPerHourSquared(v);
  }
  return v;
}

sim::NoiseTerm TermFor(Coefficient c, double v) {
  switch (c) {
    case Coefficient::kQ: return sim::QuantizationNoise{v};
    case Coefficient::kN: return sim::WhiteRateNoise{v};
    case Coefficient::kB: return sim::FlickerNoise{v};
    case Coefficient::kK: return sim::RandomWalkRate{v};
    case Coefficient::kR: return sim::RateRamp{v};
  }
  return sim::WhiteRateNoise{v};
}

double AsymptoteShape(Coefficient c, double tau) {
  switch (c) {
    case Coefficient::kQ: return 3.0 / (tau * tau);
    case Coefficient::kN: return 1.0 / tau;
    case Coefficient::kB: return 2.0 * std::numbers::ln2 / std::numbers::pi;
    case Coefficient::kK: return tau / 3.0;
    case Coefficient::kR: return 0.5 * tau * tau;
  }
  return 0.0;
}

}  // namespace allanlab::estimators
