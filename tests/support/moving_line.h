#pragma once
// A record of a spectral line that moves, written for the tests apart from sim/ and independent/:
// a second-order resonance x_k = 2 r cos(theta_k) x_{k-1} - r^2 x_{k-2} + g_k e_k in white noise,
// theta_k = 2 pi f_k / fs, r = exp(-zeta theta_k), its frequency f_k and its stationary standard
// deviation sigma_k going linearly from the first sample's to the last's. g_k holds that standard
// deviation as the pole turns: Var(x) = (1 + r^2) / ((1 - r^2) ((1 + r^2)^2 - 4 r^2 cos^2 theta))
// per unit innovation variance. std::mt19937_64 draws; the oscillator runs 2000 samples before
// the record to forget its zero start.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

namespace allanlab::testing {

struct MovingLineSpec {
  double rate_hz = 100.0;
  std::int64_t samples = 0;
  double damping = 0.04;
  double f_first_hz = 0.0, f_last_hz = 0.0;  // at the first and the last sample
  double sigma_first = 0.0, sigma_last = 0.0;  // the line's rms [rad/s]
  double white_sigma = 0.0;                  // white noise per sample [rad/s]
};

inline std::vector<double> MovingLine(const MovingLineSpec& m, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  std::normal_distribution<double> normal;
  std::vector<double> y(static_cast<std::size_t>(m.samples));
  double x1 = 0.0, x2 = 0.0;
  for (std::int64_t k = -2000; k < m.samples; ++k) {
    const double s = std::max(0.0, static_cast<double>(k)) / static_cast<double>(m.samples - 1);
    const double theta = 2.0 * std::numbers::pi * (m.f_first_hz + s * (m.f_last_hz - m.f_first_hz)) / m.rate_hz;
    const double r = std::exp(-m.damping * theta);
    const double c = std::cos(theta);
    const double var = (1.0 + r * r) / ((1.0 - r * r) * ((1.0 + r * r) * (1.0 + r * r) - 4.0 * r * r * c * c));
    const double sigma = m.sigma_first + s * (m.sigma_last - m.sigma_first);
    const double x = 2.0 * r * c * x1 - r * r * x2 + sigma / std::sqrt(var) * normal(engine);
    x2 = x1;
    x1 = x;
    if (k >= 0) y[static_cast<std::size_t>(k)] = x + m.white_sigma * normal(engine);
  }
  return y;
}

}  // namespace allanlab::testing
