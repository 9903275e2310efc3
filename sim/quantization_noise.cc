#include "sim/quantization_noise.h"

#include <algorithm>

#include <boost/random/normal_distribution.hpp>

namespace allanlab::sim {

bool QuantizationNoise::IsValid(std::string* why) const {
  return CheckNonNegative(q_rad, "quantization Q", why);
}

void QuantizationNoise::AddTo(Engine& engine, double tau0_s, std::span<double> rate) const {
  if (q_rad == 0.0) return;
  boost::random::normal_distribution<double> normal(0.0, q_rad);
  double previous = normal(engine);
  for (double& v : rate) {
    const double theta = normal(engine);
    v += (theta - previous) / tau0_s;
    previous = theta;
  }
}

void QuantizationNoise::FillAutocovariance(double tau0_s, std::span<double> r) const {
  std::fill(r.begin(), r.end(), 0.0);
  const double unit = q_rad * q_rad / (tau0_s * tau0_s);
  if (r.size() > 0) r[0] = 2.0 * unit;
  if (r.size() > 1) r[1] = -unit;
}

double QuantizationNoise::ExpectedAvar(std::int64_t m, double tau0_s, const RecordShape&) const {
  return AsymptoticAvar(static_cast<double>(m) * tau0_s);
}

double QuantizationNoise::AsymptoticAvar(double tau_s) const {
  return 3.0 * q_rad * q_rad / (tau_s * tau_s);
}

}  // namespace allanlab::sim
