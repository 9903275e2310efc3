#pragma once
// Exponential warm-up drift a e^{-t/tau_w} (t from the start of the record): the bias settling
// after power-on, a classic reason why the long-tau end of a real Allan curve rises.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sim/avar_theory.h"
#include "sim/term_common.h"

namespace allanlab::sim {

struct ExponentialDrift {
  static constexpr std::string_view kId = "exponential_drift";
  static constexpr SignalPath kPath = SignalPath::kHeld;

  double amplitude_rad_per_s = 0.0;  // a (sign free)
  double time_constant_s = 600.0;    // tau_w

  bool IsValid(std::string* why) const;
  // rate[k] += a e^{-k tau0 / tau_w} (no randomness).
  // Sample k of `rate` is the signal at index first_index + k (negative: before the record).
  void AddTo(Engine& engine, double tau0_s, std::span<double> rate_rad_per_s,
             std::int64_t first_index = 0) const;
  // Exact estimator value on the record (closed-form geometric sums): depends on N and on the
  // estimator. With `held_response` (a band-limit's q_j), the filtered drift is the same
  // exponential scaled by sum_j q_j e^{j tau0/tau_w}.
  double ExpectedAvar(std::int64_t m, double tau0_s, const RecordShape& shape,
                      const std::vector<double>& held_response = {}) const;
  // The drift on the output samples is a' e^{-k tau0 / tau_w} (held: a band-limit's response q
  // to the exponential is the exponential again): a' = a sum_j q_j e^{j tau0 / tau_w}, a without
  // `held_response`.
  double OutputAmplitude(double tau0_s, const std::vector<double>& held_response = {}) const;
};

}  // namespace allanlab::sim
