#pragma once
// Harmonic (sinusoidal) rate term: Omega0 sin(2 pi f0 t + phase), e.g. a mechanical resonance or
// a mains pick-up. IEEE Std 952 "sinusoidal noise".
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "sim/avar_theory.h"
#include "sim/term_common.h"

namespace allanlab::sim {

// Exact estimator expectation for point samples A sin(omega k + phase), omega = 2 pi f0 tau0.
// Random phase (nullopt): AVAR(m) = A^2 sin^4(pi f0 m tau0) / (m sin(pi f0 tau0))^2
// (docs/theory.md §2.7). Fixed phase: the exact finite-record value, which oscillates about it.
double SampledSinusoidAvar(double amplitude, double f0_hz, double tau0_s,
                           std::optional<double> phase_rad, std::int64_t m,
                           const RecordShape& shape);

struct Harmonic {
  static constexpr std::string_view kId = "harmonic";
  static constexpr SignalPath kPath = SignalPath::kWideband;

  double amplitude_rad_per_s = 0.0;   // Omega0 (peak)
  double frequency_hz = 1.0;          // f0
  std::optional<double> phase_rad;    // fixed phase at t = 0, or uniform random per realisation

  bool IsValid(std::string* why) const;
  // The phase of one realisation: the fixed phase, or one uniform draw in [0, 2 pi).
  double DrawPhase(Engine& engine) const;
  // rate[k] += Omega0 sin(2 pi f0 (first_index + k) tau + phase).
  void AddSamples(double phase_rad_value, double tau_s, std::int64_t first_index,
                  std::span<double> rate_rad_per_s) const;
  void AddTo(Engine& engine, double tau0_s, std::span<double> rate_rad_per_s) const;
  // Exact point-sampled form (random phase: closed form; fixed phase: finite-record exact).
  double ExpectedAvar(std::int64_t m, double tau0_s, const RecordShape& shape) const;
  // Continuous, phase-averaged: Omega0^2 (sin^2(pi f0 tau) / (pi f0 tau))^2. The ratio is
  // squared; the seed paper (Mikheev et al. 2021) prints it unsquared, which decays as 1/tau
  // instead of 1/tau^2 and is 4.7x too large at f0 tau = 1.5 (docs/theory.md §8.1).
  double AsymptoticAvar(double tau_s) const;
};

}  // namespace allanlab::sim
