#include "sim/harmonic.h"

#include <cmath>
#include <numbers>

#include <boost/random/uniform_real_distribution.hpp>

namespace allanlab::sim {
namespace {
constexpr double kTwoPi = 2.0 * std::numbers::pi;

// sum_{i<n} cos(a i + b) in closed form (Dirichlet kernel).
double CosineSum(std::int64_t n, double a, double b) {
  const double half = 0.5 * a;
  const double s = std::sin(half);
  if (std::abs(s) < 1e-300) return static_cast<double>(n) * std::cos(b);
  return std::sin(static_cast<double>(n) * half) / s * std::cos(b + (n - 1) * half);
}
}  // namespace

double SampledSinusoidAvar(double amplitude, double f0_hz, double tau0_s,
                           std::optional<double> phase_rad, std::int64_t m,
                           const RecordShape& shape) {
  const double omega = kTwoPi * f0_hz * tau0_s;  // rad per sample
  const double s1 = std::sin(0.5 * omega);
  if (std::abs(s1) < 1e-15) return 0.0;  // f0 a multiple of fs: the samples are constant
  const double sm = std::sin(0.5 * omega * static_cast<double>(m));
  // D_t = A_d cos(omega t + chi), A_d = 2 A sin^2(m omega/2) / (m sin(omega/2)).
  const double ad = 2.0 * amplitude * sm * sm / (static_cast<double>(m) * s1);
  const double random_phase_value = 0.25 * ad * ad;
  if (!phase_rad) return random_phase_value;
  const AllanStarts starts = AllanDifferenceStarts(m, shape);
  if (starts.count == 0) return 0.0;
  const double chi = *phase_rad + (static_cast<double>(m) - 0.5) * omega;
  const double oscillation =
      CosineSum(starts.count, 2.0 * omega * static_cast<double>(starts.stride), 2.0 * chi) /
      static_cast<double>(starts.count);
  return random_phase_value * (1.0 + oscillation);
}

bool Harmonic::IsValid(std::string* why) const {
  if (!CheckNonNegative(amplitude_rad_per_s, "harmonic amplitude Omega0", why)) return false;
  if (!CheckPositive(frequency_hz, "harmonic frequency f0", why)) return false;
  if (phase_rad && !std::isfinite(*phase_rad)) {
    if (why) *why = "harmonic phase must be finite";
    return false;
  }
  return true;
}

double Harmonic::DrawPhase(Engine& engine) const {
  if (phase_rad) return *phase_rad;
  boost::random::uniform_real_distribution<double> uniform(0.0, kTwoPi);
  return uniform(engine);
}

void Harmonic::AddSamples(double phase, double tau_s, std::int64_t first_index,
                          std::span<double> rate) const {
  if (amplitude_rad_per_s == 0.0) return;
  // Cycles per sample reduced mod 1 keeps the phase exact for long records.
  const double cycles = frequency_hz * tau_s;
  const double step = kTwoPi * (cycles - std::floor(cycles));
  const double cos_step = std::cos(step), sin_step = std::sin(step);
  constexpr std::size_t kReanchor = 1024;  // bound the rotation's rounding drift
  for (std::size_t start = 0; start < rate.size(); start += kReanchor) {
    const long double index = static_cast<long double>(first_index) + start;
    const long double turns = index * static_cast<long double>(cycles);
    const double angle = kTwoPi * static_cast<double>(turns - std::floor(turns)) + phase;
    double s = std::sin(angle), c = std::cos(angle);
    const std::size_t end = std::min(rate.size(), start + kReanchor);
    for (std::size_t k = start; k < end; ++k) {
      rate[k] += amplitude_rad_per_s * s;
      const double s_next = s * cos_step + c * sin_step;
      c = c * cos_step - s * sin_step;
      s = s_next;
    }
  }
}

void Harmonic::AddTo(Engine& engine, double tau0_s, std::span<double> rate) const {
  AddSamples(DrawPhase(engine), tau0_s, 0, rate);
}

double Harmonic::ExpectedAvar(std::int64_t m, double tau0_s, const RecordShape& shape) const {
  return SampledSinusoidAvar(amplitude_rad_per_s, frequency_hz, tau0_s, phase_rad, m, shape);
}

double Harmonic::AsymptoticAvar(double tau_s) const {
  const double x = std::numbers::pi * frequency_hz * tau_s;
  const double ratio = std::sin(x) * std::sin(x) / x;
  return amplitude_rad_per_s * amplitude_rad_per_s * ratio * ratio;
}

}  // namespace allanlab::sim
