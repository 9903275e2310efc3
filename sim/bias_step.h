#pragma once
// A bias step of size b at time t_step (a temperature jump, a mode change): a deterministic
// non-stationarity that the first-half / second-half and dynamic Allan views expose.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sim/avar_theory.h"
#include "sim/term_common.h"

namespace allanlab::sim {

struct BiasStep {
  static constexpr std::string_view kId = "bias_step";
  static constexpr SignalPath kPath = SignalPath::kHeld;

  double size_rad_per_s = 0.0;  // b
  double time_s = 0.0;          // t_step, from the start of the record

  bool IsValid(std::string* why) const;
  // rate[k] += b for k tau0 >= t_step.
  // Sample k of `rate` is the signal at index first_index + k (negative: before the record).
  void AddTo(Engine& engine, double tau0_s, std::span<double> rate_rad_per_s,
             std::int64_t first_index = 0) const;
  // Exact estimator value on the record; with `held_response` (a band-limit's q_j), of the
  // filtered step.
  // Without a band-limit the value is memoised per thread by (b, step index, m, shape): a held
  // step is assessed at the same curve in every pass of a refit and fit evaluation, O(m) each.
  double ExpectedAvar(std::int64_t m, double tau0_s, const RecordShape& shape,
                      const std::vector<double>& held_response = {}) const;
  // The same computed afresh (no memo).
  double ExpectedAvarUncached(std::int64_t m, double tau0_s, const RecordShape& shape,
                              const std::vector<double>& held_response = {}) const;
  std::int64_t StepIndex(double tau0_s) const;
};

}  // namespace allanlab::sim
