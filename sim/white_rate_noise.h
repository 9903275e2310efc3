#pragma once
// Angle random walk: white rate noise (IEEE Std 952, coefficient N).
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "sim/avar_theory.h"
#include "sim/term_common.h"

namespace allanlab::sim {

struct WhiteRateNoise {
  static constexpr std::string_view kId = "arw";
  static constexpr SignalPath kPath = SignalPath::kWideband;

  // N in rad/sqrt(s) (= rad/s/sqrt(Hz)); per-sample std is N / sqrt(tau0).
  double arw_rad_per_sqrt_s = 0.0;

  bool IsValid(std::string* why) const;
  // rate[k] += N / sqrt(tau0) * z_k.
  void AddTo(Engine& engine, double tau0_s, std::span<double> rate_rad_per_s) const;
  // R(0) = N^2 / tau0, R(j != 0) = 0, in (rad/s)^2.
  void FillAutocovariance(double tau0_s, std::span<double> r) const;
  // Exact: AVAR(m) = N^2 / (m tau0) for every m (docs/theory.md §2.2).
  double ExpectedAvar(std::int64_t m, double tau0_s, const RecordShape& shape) const;
  // IEEE 952: N^2 / tau.
  double AsymptoticAvar(double tau_s) const;
};

}  // namespace allanlab::sim
