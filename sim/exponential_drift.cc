#include "sim/exponential_drift.h"

#include <cmath>

namespace allanlab::sim {

bool ExponentialDrift::IsValid(std::string* why) const {
  if (!std::isfinite(amplitude_rad_per_s)) {
    if (why) *why = "exponential_drift amplitude must be finite";
    return false;
  }
  return CheckPositive(time_constant_s, "exponential_drift time constant", why);
}

void ExponentialDrift::AddTo(Engine&, double tau0_s, std::span<double> rate,
                             std::int64_t first_index) const {
  for (std::size_t k = 0; k < rate.size(); ++k) {
    const auto index = static_cast<double>(first_index + static_cast<std::int64_t>(k));
    rate[k] += amplitude_rad_per_s * std::exp(-index * tau0_s / time_constant_s);
  }
}

double ExponentialDrift::ExpectedAvar(std::int64_t m, double tau0_s, const RecordShape& shape,
                                      const std::vector<double>& held_response) const {
  const AllanStarts starts = AllanDifferenceStarts(m, shape);
  if (starts.count == 0) return 0.0;
  const double x = tau0_s / time_constant_s;  // -ln(rho)
  const double a = OutputAmplitude(tau0_s, held_response);
  // D_t = -(a/m) rho^t (1 - rho^m)^2 / (1 - rho); mean over t = i * stride of D_t^2 / 2.
  const double one_minus_rho_m = -std::expm1(-x * static_cast<double>(m));
  const double one_minus_rho = -std::expm1(-x);
  const double d0 = a / static_cast<double>(m) * one_minus_rho_m * one_minus_rho_m / one_minus_rho;
  const double r2 = 2.0 * x * static_cast<double>(starts.stride);  // -ln(rho^{2 stride})
  const double geometric = -std::expm1(-r2 * static_cast<double>(starts.count)) / -std::expm1(-r2);
  return 0.5 * d0 * d0 * geometric / static_cast<double>(starts.count);
}

double ExponentialDrift::OutputAmplitude(double tau0_s, const std::vector<double>& held_response) const {
  if (held_response.empty()) return amplitude_rad_per_s;
  const double x = tau0_s / time_constant_s;
  double gain = 0.0;
  for (std::size_t j = 0; j < held_response.size(); ++j) gain += held_response[j] * std::exp(static_cast<double>(j) * x);
  return amplitude_rad_per_s * gain;
}

}  // namespace allanlab::sim
