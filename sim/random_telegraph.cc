#include "sim/random_telegraph.h"

#include <cmath>

#include "sim/gauss_markov.h"

namespace allanlab::sim {

bool RandomTelegraph::IsValid(std::string* why) const {
  return CheckNonNegative(amplitude_rad_per_s, "random_telegraph amplitude a", why) &&
         CheckPositive(mean_dwell_s, "random_telegraph mean dwell", why);
}

void RandomTelegraph::AddTo(Engine& engine, double tau0_s, std::span<double> rate) const {
  if (amplitude_rad_per_s == 0.0) return;
  const double flip_probability = -0.5 * std::expm1(-2.0 * tau0_s / mean_dwell_s);
  // p < 1/2 always, so p * 2^64 fits in 64 bits. Comparing raw draws with it is exact and
  // needs no floating-point work per sample.
  const auto threshold = static_cast<std::uint64_t>(std::ldexp(flip_probability, 64));
  double level = (engine() >> 63) ? amplitude_rad_per_s : -amplitude_rad_per_s;
  for (double& v : rate) {
    v += level;
    if (engine() < threshold) level = -level;
  }
}

void RandomTelegraph::FillAutocovariance(double tau0_s, std::span<double> r, std::int64_t first_lag) const {
  FillAr1Autocovariance(std::exp(-2.0 * tau0_s / mean_dwell_s),
                        amplitude_rad_per_s * amplitude_rad_per_s, r, first_lag);
}

double RandomTelegraph::ExpectedAvar(std::int64_t m, double tau0_s, const RecordShape&) const {
  return Ar1Avar(m, std::exp(-2.0 * tau0_s / mean_dwell_s),
                 amplitude_rad_per_s * amplitude_rad_per_s);
}

double RandomTelegraph::AsymptoticAvar(double tau_s) const {
  return GaussMarkov{amplitude_rad_per_s, 0.5 * mean_dwell_s}.AsymptoticAvar(tau_s);
}

}  // namespace allanlab::sim
