#include "sim/rate_ramp.h"

#include <cmath>

namespace allanlab::sim {

bool RateRamp::IsValid(std::string* why) const {
  if (!std::isfinite(ramp_rad_per_s2)) {
    if (why) *why = "rate ramp R must be finite";
    return false;
  }
  return true;
}

void RateRamp::AddTo(Engine&, double tau0_s, std::span<double> rate,
                     std::int64_t first_index) const {
  for (std::size_t k = 0; k < rate.size(); ++k) {
    rate[k] += ramp_rad_per_s2 * static_cast<double>(first_index + static_cast<std::int64_t>(k)) *
               tau0_s;
  }
}

double RateRamp::ExpectedAvar(std::int64_t m, double tau0_s, const RecordShape&) const {
  return AsymptoticAvar(static_cast<double>(m) * tau0_s);
}

double RateRamp::AsymptoticAvar(double tau_s) const {
  return 0.5 * ramp_rad_per_s2 * ramp_rad_per_s2 * tau_s * tau_s;
}

}  // namespace allanlab::sim
