#include "sim/random_walk_rate.h"

#include <cmath>

#include <boost/random/normal_distribution.hpp>

namespace allanlab::sim {

bool RandomWalkRate::IsValid(std::string* why) const {
  return CheckNonNegative(rrw_rad_per_s_per_sqrt_s, "rate random walk K", why);
}

void RandomWalkRate::AddTo(Engine& engine, double tau0_s, std::span<double> rate) const {
  if (rrw_rad_per_s_per_sqrt_s == 0.0) return;
  boost::random::normal_distribution<double> normal(0.0, 1.0);
  const double step_std = rrw_rad_per_s_per_sqrt_s * std::sqrt(tau0_s);
  double level = 0.0;
  for (double& v : rate) {
    level += step_std * normal(engine);
    v += level;
  }
}

void RandomWalkRate::FillAutocovariance(double tau0_s, std::span<double> r) const {
  const double step_var = rrw_rad_per_s_per_sqrt_s * rrw_rad_per_s_per_sqrt_s * tau0_s;
  for (std::size_t j = 0; j < r.size(); ++j) r[j] = -0.5 * static_cast<double>(j) * step_var;
}

double RandomWalkRate::ExpectedAvar(std::int64_t m, double tau0_s, const RecordShape&) const {
  const double tau = static_cast<double>(m) * tau0_s;
  const double k2 = rrw_rad_per_s_per_sqrt_s * rrw_rad_per_s_per_sqrt_s;
  return k2 * tau / 3.0 + k2 * tau0_s * tau0_s / (6.0 * tau);
}

double RandomWalkRate::AsymptoticAvar(double tau_s) const {
  return rrw_rad_per_s_per_sqrt_s * rrw_rad_per_s_per_sqrt_s * tau_s / 3.0;
}

}  // namespace allanlab::sim
