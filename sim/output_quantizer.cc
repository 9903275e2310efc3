#include "sim/output_quantizer.h"

#include <cmath>

#include <boost/random/uniform_real_distribution.hpp>

#include "sim/term_common.h"

namespace allanlab::sim {

bool AngleQuantizer::IsValid(std::string* why) const {
  return CheckPositive(lsb_rad, "angle quantizer LSB", why);
}

void AngleQuantizer::Apply(Engine& engine, double tau0_s, std::span<double> rate) const {
  boost::random::uniform_real_distribution<double> uniform(0.0, 1.0);
  // Angle in LSB units; long double keeps the residual exact over long, biased records.
  long double angle_lsb = uniform(engine);
  long double previous_count = std::floor(angle_lsb);
  const long double per_rate = tau0_s / static_cast<long double>(lsb_rad);
  for (double& v : rate) {
    angle_lsb += v * per_rate;
    const long double count = std::floor(angle_lsb);
    v = static_cast<double>((count - previous_count) * lsb_rad / tau0_s);
    previous_count = count;
  }
}

double AngleQuantizer::ApproximateAvar(double tau_s) const {
  return lsb_rad * lsb_rad / (4.0 * tau_s * tau_s);
}

bool RateQuantizer::IsValid(std::string* why) const {
  return CheckPositive(lsb_rad_per_s, "rate quantizer LSB", why);
}

void RateQuantizer::Apply(std::span<double> rate) const {
  for (double& v : rate) v = lsb_rad_per_s * std::nearbyint(v / lsb_rad_per_s);
}

double RateQuantizer::ApproximateAvar(std::int64_t m) const {
  return lsb_rad_per_s * lsb_rad_per_s / (12.0 * static_cast<double>(m));
}

}  // namespace allanlab::sim
