#pragma once
// Random telegraph signal (bias flips, "popcorn" noise): the rate bias jumps between +a and -a
// with exponentially distributed dwell times. Its autocovariance a^2 exp(-2|t|/T_dwell) equals
// that of a Gauss-Markov process with sigma = a, Tc = T_dwell/2, so its Allan variance is the same
// (only the sample distribution tells them apart).
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "sim/avar_theory.h"
#include "sim/term_common.h"

namespace allanlab::sim {

struct RandomTelegraph {
  static constexpr std::string_view kId = "random_telegraph";
  static constexpr SignalPath kPath = SignalPath::kHeld;

  double amplitude_rad_per_s = 0.0;  // a: the bias is +a or -a
  double mean_dwell_s = 1.0;         // mean time between flips

  bool IsValid(std::string* why) const;
  // Two-state Markov chain at the output rate, flip probability p = (1 - e^{-2 tau0/T})/2 per
  // sample (so the sampled autocovariance is exactly a^2 e^{-2|t|/T}), random initial state.
  void AddTo(Engine& engine, double tau0_s, std::span<double> rate_rad_per_s) const;
  // Lags first_lag .. first_lag + r.size() - 1.
  void FillAutocovariance(double tau0_s, std::span<double> r, std::int64_t first_lag = 0) const;
  // Exact: AR(1) form with phi = e^{-2 tau0/T}, variance a^2.
  double ExpectedAvar(std::int64_t m, double tau0_s, const RecordShape& shape) const;
  // Continuous limit: OU Allan variance with sigma = a, Tc = T/2.
  double AsymptoticAvar(double tau_s) const;
};

}  // namespace allanlab::sim
