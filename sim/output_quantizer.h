#pragma once
// Digitisation effects beyond the IEEE 952 model, applied to the sensor's output:
//  * AngleQuantizer: a quantizer on the integrated angle with carry, as delta-angle outputs do
//    (the residual is kept, so no angle is lost); it adds IEEE quantization noise with
//    Q = lsb / sqrt(12) when the angle moves over many LSBs (THEORY.md §1a).
//  * RateQuantizer: each rate sample rounded to an LSB; it adds white noise of variance lsb^2/12
//    when the rate noise spans several LSBs, and strongly distorts the curve when it does not.
#include <cstdint>
#include <span>
#include <string>

#include "sim/seeding.h"

namespace allanlab::sim {

struct AngleQuantizer {
  double lsb_rad = 0.0;  // angle LSB q
  bool IsValid(std::string* why) const;
  // rate[k] <- (Qz(theta_k) - Qz(theta_{k-1})) / tau0 with theta the running angle plus a
  // uniform random initial residual drawn from `engine`.
  void Apply(Engine& engine, double tau0_s, std::span<double> rate_rad_per_s) const;
  // Approximate added AVAR: 3 (q^2/12) / tau^2 = q^2 / (4 tau^2).
  double ApproximateAvar(double tau_s) const;
};

struct RateQuantizer {
  double lsb_rad_per_s = 0.0;  // rate LSB
  bool IsValid(std::string* why) const;
  // rate[k] <- lsb * round(rate[k] / lsb).
  void Apply(std::span<double> rate_rad_per_s) const;
  // Approximate added AVAR: (lsb^2 / 12) / m.
  double ApproximateAvar(std::int64_t m) const;
};

}  // namespace allanlab::sim
