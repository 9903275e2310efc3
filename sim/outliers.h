#pragma once
// Impulsive outliers: isolated spikes of fixed size and random sign (data-link glitches,
// shocks). They add white noise of variance p a^2 to the Allan variance but are strongly
// non-Gaussian (the kurtosis of the record shows them).
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "sim/avar_theory.h"
#include "sim/term_common.h"

namespace allanlab::sim {

// Sign of the spikes: random (+-, equally likely), or all of one sign (a one-sided glitch, e.g.
// a saturating read-out or a shock from one side: the spikes then also shift the mean).
enum class SpikeSign { kSymmetric, kPositive, kNegative };
// Magnitude law: every spike of size a, or exponentially distributed with mean a (heavy-tailed
// records: MTi-G's spikes run from 6 to 44 sigma).
enum class SpikeSize { kFixed, kExponential };

struct Outliers {
  static constexpr std::string_view kId = "outliers";
  static constexpr SignalPath kPath = SignalPath::kDigital;

  double rate_hz = 0.0;             // mean number of spikes per second
  double size_rad_per_s = 0.0;      // spike magnitude a (fixed), or its mean (exponential)
  SpikeSign sign = SpikeSign::kSymmetric;
  SpikeSize size_law = SpikeSize::kFixed;

  bool IsValid(std::string* why) const;
  // Each sample independently carries a spike with probability p = rate * tau0 (needs p <= 1).
  // Fixed symmetric spikes take one 64-bit draw per sample; the other laws a second one per spike.
  void AddTo(Engine& engine, double tau0_s, std::span<double> rate_rad_per_s) const;
  // Exact: Var(spike per sample) / m for iid spikes, Var = p E[a^2] - (p E[signed a])^2 with
  // E[a^2] = a^2 (fixed) or 2 a^2 (exponential), E[signed a] = 0 (symmetric) or +-a (one-sided).
  double ExpectedAvar(std::int64_t m, double tau0_s, const RecordShape& shape) const;
  // The same Var * tau0 / tau: depends on tau0, so this is the same expression.
  double AsymptoticAvar(double tau_s, double tau0_s) const;
};

}  // namespace allanlab::sim
