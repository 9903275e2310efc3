#pragma once
// Quantization noise (IEEE Std 952, coefficient Q): the first difference of white angle noise.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "sim/avar_theory.h"
#include "sim/term_common.h"

namespace allanlab::sim {

struct QuantizationNoise {
  static constexpr std::string_view kId = "quantization";
  static constexpr SignalPath kPath = SignalPath::kDigital;

  // Q in rad: the std of the white angle noise theta_k (a uniform quantizer of step S has
  // Q = S / sqrt(12)).
  double q_rad = 0.0;

  bool IsValid(std::string* why) const;
  // rate[k] += (theta_k - theta_{k-1}) / tau0 with theta iid N(0, Q^2) (theta_{-1} drawn too,
  // so the output is stationary from k = 0).
  void AddTo(Engine& engine, double tau0_s, std::span<double> rate_rad_per_s) const;
  // R(0) = 2 Q^2 / tau0^2, R(1) = -Q^2 / tau0^2, zero beyond.
  void FillAutocovariance(double tau0_s, std::span<double> r) const;
  // Exact for every m: AVAR = 3 Q^2 / tau^2 (docs/theory.md §2.1: the Allan difference telescopes).
  double ExpectedAvar(std::int64_t m, double tau0_s, const RecordShape& shape) const;
  double AsymptoticAvar(double tau_s) const;
};

}  // namespace allanlab::sim
