#pragma once
// Bias instability approximated by a sum of first-order Gauss-Markov processes with time
// constants spaced geometrically by a ratio r (the "GM bank" used in many navigation filters).
// With equal variances q = B^2 ln(r) / pi the sum has h_{-1} = B^2 / pi between the extreme time
// constants (docs/theory.md §2.5.5). Ripple of AVAR / ((2 ln2/pi) B^2) for tau well inside the bank:
// 0.982..1.020 at one process per decade, 0.9992..1.0001 at r = 3 (see AvarRipple).
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "sim/avar_theory.h"
#include "sim/term_common.h"

namespace allanlab::sim {

struct FlickerGaussMarkovSum {
  static constexpr std::string_view kId = "bias_instability_gm_sum";
  static constexpr SignalPath kPath = SignalPath::kHeld;

  double bias_instability_rad_per_s = 0.0;  // B (IEEE 952)
  double min_correlation_time_s = 1e-2;     // shortest Tc of the bank
  double max_correlation_time_s = 1e5;      // longest Tc of the bank
  double processes_per_decade = 1.0;        // 1/log10(r)

  bool IsValid(std::string* why) const;
  std::vector<double> CorrelationTimes() const;
  // Per-process stationary variance q = B^2 ln(r) / pi.
  double ProcessVariance() const;
  void AddTo(Engine& engine, double tau0_s, std::span<double> rate_rad_per_s) const;
  // Lags first_lag .. first_lag + r.size() - 1.
  void FillAutocovariance(double tau0_s, std::span<double> r, std::int64_t first_lag = 0) const;
  // Exact: the sum of the AR(1) Allan variances.
  double ExpectedAvar(std::int64_t m, double tau0_s, const RecordShape& shape) const;
  // Sum of the continuous OU Allan variances.
  double AsymptoticAvar(double tau_s) const;
  // {min, max} of AsymptoticAvar / ((2 ln2/pi) B^2) over a log grid of taus in [lo, hi].
  std::pair<double, double> AvarRipple(double tau_lo_s, double tau_hi_s) const;
};

}  // namespace allanlab::sim
