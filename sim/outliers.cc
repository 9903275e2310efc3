#include "sim/outliers.h"

#include <cmath>

namespace allanlab::sim {

bool Outliers::IsValid(std::string* why) const {
  return CheckNonNegative(rate_hz, "outliers rate", why) &&
         CheckNonNegative(size_rad_per_s, "outliers size", why);
}

void Outliers::AddTo(Engine& engine, double tau0_s, std::span<double> rate) const {
  const double p = rate_hz * tau0_s;
  if (p <= 0.0 || size_rad_per_s == 0.0) return;
  // One 64-bit draw per sample: the top bit gives the sign, the rest the Bernoulli trial.
  const auto threshold = static_cast<std::uint64_t>(std::ldexp(std::min(p, 1.0), 63));
  for (double& v : rate) {
    const std::uint64_t u = engine();
    if ((u >> 1) >= threshold) continue;
    double size = size_rad_per_s;
    if (size_law == SpikeSize::kExponential) {
      // -ln(1 - U) with U in [0, 1) from the top 53 bits of a second draw.
      const double uniform = std::ldexp(static_cast<double>(engine() >> 11), -53);
      size = -size_rad_per_s * std::log1p(-uniform);
    }
    if (sign == SpikeSign::kPositive) {
      v += size;
    } else if (sign == SpikeSign::kNegative) {
      v -= size;
    } else {
      v += (u & 1U) ? size : -size;
    }
  }
}

double Outliers::ExpectedAvar(std::int64_t m, double tau0_s, const RecordShape&) const {
  return AsymptoticAvar(static_cast<double>(m) * tau0_s, tau0_s);
}

double Outliers::AsymptoticAvar(double tau_s, double tau0_s) const {
  const double p = std::min(rate_hz * tau0_s, 1.0);
  const double second = (size_law == SpikeSize::kExponential ? 2.0 : 1.0) * size_rad_per_s * size_rad_per_s;
  const double mean = sign == SpikeSign::kSymmetric ? 0.0 : p * size_rad_per_s;
  return (p * second - mean * mean) * tau0_s / tau_s;
}

}  // namespace allanlab::sim
