#include "sim/white_rate_noise.h"

#include <algorithm>
#include <cmath>

namespace allanlab::sim {

bool WhiteRateNoise::IsValid(std::string* why) const {
  return CheckNonNegative(arw_rad_per_sqrt_s, "arw N", why);
}

void WhiteRateNoise::AddTo(Engine& engine, double tau0_s, std::span<double> rate) const {
  AddGaussian(engine, arw_rad_per_sqrt_s / std::sqrt(tau0_s), rate);
}

void WhiteRateNoise::FillAutocovariance(double tau0_s, std::span<double> r) const {
  std::fill(r.begin(), r.end(), 0.0);
  if (!r.empty()) r[0] = arw_rad_per_sqrt_s * arw_rad_per_sqrt_s / tau0_s;
}

double WhiteRateNoise::ExpectedAvar(std::int64_t m, double tau0_s, const RecordShape&) const {
  return AsymptoticAvar(static_cast<double>(m) * tau0_s);
}

double WhiteRateNoise::AsymptoticAvar(double tau_s) const {
  return arw_rad_per_sqrt_s * arw_rad_per_sqrt_s / tau_s;
}

}  // namespace allanlab::sim
