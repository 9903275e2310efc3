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

struct Outliers {
  static constexpr std::string_view kId = "outliers";
  static constexpr SignalPath kPath = SignalPath::kDigital;

  double rate_hz = 0.0;             // mean number of spikes per second
  double size_rad_per_s = 0.0;      // spike magnitude a (sign random)

  bool IsValid(std::string* why) const;
  // Each sample independently carries a spike with probability p = rate * tau0 (needs p <= 1).
  void AddTo(Engine& engine, double tau0_s, std::span<double> rate_rad_per_s) const;
  // Exact: p a^2 / m (iid zero-mean spikes).
  double ExpectedAvar(std::int64_t m, double tau0_s, const RecordShape& shape) const;
  // rate * a^2 * tau0 / tau: depends on tau0, so this is the same expression.
  double AsymptoticAvar(double tau_s, double tau0_s) const;
};

}  // namespace allanlab::sim
