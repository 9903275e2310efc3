#pragma once
// Rate random walk (IEEE Std 952, coefficient K): a discrete random walk of the rate.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "sim/avar_theory.h"
#include "sim/term_common.h"

namespace allanlab::sim {

struct RandomWalkRate {
  static constexpr std::string_view kId = "rrw";
  static constexpr SignalPath kPath = SignalPath::kHeld;

  // K in rad/s/sqrt(s) (= rad/s^2/sqrt(Hz)); step variance K^2 tau0.
  double rrw_rad_per_s_per_sqrt_s = 0.0;

  bool IsValid(std::string* why) const;
  // y_k = y_{k-1} + w_k, w ~ N(0, K^2 tau0), y_{-1} = 0.
  void AddTo(Engine& engine, double tau0_s, std::span<double> rate_rad_per_s) const;
  // Generalised autocovariance R(j) = -|j| K^2 tau0 / 2.
  void FillAutocovariance(double tau0_s, std::span<double> r) const;
  // Exact: AVAR = K^2 tau / 3 + K^2 tau0^2 / (6 tau) (docs/theory.md §2.3).
  double ExpectedAvar(std::int64_t m, double tau0_s, const RecordShape& shape) const;
  // IEEE 952: K^2 tau / 3.
  double AsymptoticAvar(double tau_s) const;
};

}  // namespace allanlab::sim
