#pragma once
// The IEEE Std 952 coefficients a fit recovers, their datasheet units, and the sim term that
// carries each one's exact Allan-variance shape (so there is one place that knows it: sim/).
#include <string_view>

#include "sim/noise_term.h"

namespace allanlab::estimators {

enum class Coefficient { kQ, kN, kB, kK, kR };
inline constexpr Coefficient kAllCoefficients[] = {Coefficient::kQ, Coefficient::kN,
                                                   Coefficient::kB, Coefficient::kK,
                                                   Coefficient::kR};

// "Q", "N", "B", "K", "R".
std::string_view CoefficientId(Coefficient c);
bool ParseCoefficient(std::string_view id, Coefficient* c);

// Datasheet unit (the keys of `allanlab fit --json`): Q urad, N deg/sqrt(h), B deg/h, K deg/h/sqrt(h),
// R deg/h^2.
std::string_view DatasheetUnit(Coefficient c);
// SI value (Q rad, N rad/sqrt(s), B rad/s, K rad/s/sqrt(s), R rad/s^2) -> datasheet unit.
double ToDatasheetUnit(Coefficient c, double value_si);
double FromDatasheetUnit(Coefficient c, double datasheet_value);

// The sim term with coefficient value `si_value` (quantization, white rate, Kasdin flicker,
// random walk, ramp): its ExpectedAvar is the exact discrete shape the fit uses.
sim::NoiseTerm TermFor(Coefficient c, double value_si);

// IEEE 952 asymptote of the term at tau per unit coefficient^2:
// Q 3/tau^2, N 1/tau, B 2 ln2/pi, K tau/3, R tau^2/2.
double AsymptoteShape(Coefficient c, double tau_s);

}  // namespace allanlab::estimators
