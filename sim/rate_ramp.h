#pragma once
// Rate ramp (IEEE Std 952, coefficient R): a deterministic linear drift of the rate.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "sim/avar_theory.h"
#include "sim/term_common.h"

namespace allanlab::sim {

struct RateRamp {
  static constexpr std::string_view kId = "ramp";
  static constexpr SignalPath kPath = SignalPath::kHeld;

  double ramp_rad_per_s2 = 0.0;  // R (may be negative: the sign does not change the AVAR)

  bool IsValid(std::string* why) const;
  // rate[k] += R k tau0 (uses no randomness).
  // Sample k of `rate` is the signal at index first_index + k (negative: before the record).
  void AddTo(Engine& engine, double tau0_s, std::span<double> rate_rad_per_s,
             std::int64_t first_index = 0) const;
  // Exact for every estimator, record and unit-DC-gain filter: R^2 tau^2 / 2.
  double ExpectedAvar(std::int64_t m, double tau0_s, const RecordShape& shape) const;
  double AsymptoticAvar(double tau_s) const;
};

}  // namespace allanlab::sim
