#pragma once
// Digitisation effects beyond the IEEE 952 model, applied to the sensor's output:
//  * AngleQuantizer: a quantizer on the integrated angle with carry, as delta-angle outputs do
//    (the residual is kept, so no angle is lost); it adds IEEE quantization noise with
//    Q = lsb / sqrt(12) when the angle moves over many LSBs (docs/theory.md §2.1), and correlated error
//    when it moves less than ~1 LSB per sample (ErrorAutocovariance: exact for a Gaussian signal).
//  * RateQuantizer: each rate sample rounded to an LSB; it adds white noise of variance lsb^2/12
//    when the rate noise spans several LSBs, and correlated error that distorts the curve when it
//    does not (a band-limited or slowly wandering signal crosses few levels between samples).
//    ErrorAutocovariance gives the error's exact second moments for a Gaussian signal. With
//    subtractive dither (a uniform value of one LSB's width added before rounding and removed
//    after) the error is uniform, white and independent of the signal whatever the signal does:
//    lsb^2/12 at lag 0 exactly, and the samples sit on no value grid.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

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
  // Autocovariance R_e(j), j = 0..n-1 (rad^2), of the angle error e_k = Qz(theta_k) - theta_k
  // for a Gaussian angle whose increments over j samples have variance D(j) =
  // `increment_variance_rad2[j]` (D(0) = 0) and mean j * `mean_increment_rad` (the bias):
  //   R_e(j) = sum_{k >= 1} q^2 / (2 pi^2 k^2) cos(2 pi k j mu / q) exp(-2 pi^2 k^2 D(j) / q^2),
  // the sawtooth series of RateQuantizer::ErrorAutocovariance. Exact here without an option: Apply
  // draws the initial residual uniformly, so the grid offset is uniform and e is uncorrelated
  // with the signal. The rate error (e_k - e_{k-1}) / tau0 then adds
  //   AVAR(m) = (3 R_e(0) - 4 R_e(m) + R_e(2m)) / (m tau0)^2          (AvarFromError),
  // which is ApproximateAvar once D(1) >> q^2 (R_e(j >= 1) ~ 0).
  std::vector<double> ErrorAutocovariance(std::span<const double> increment_variance_rad2,
                                          double mean_increment_rad) const;
  // R_e beyond the span is taken as 0 (decorrelated). Precondition: m >= 1, R_e non-empty.
  static double AvarFromError(std::int64_t m, double tau0_s, std::span<const double> error_rad2);
  // The rate error's autocovariance (2 R_e(j) - R_e(j-1) - R_e(j+1)) / tau0^2 at lags 0..n-2
  // (rate^2), R_e(-1) = R_e(1).
  static std::vector<double> RateErrorAutocovariance(double tau0_s, std::span<const double> error_rad2);
};

struct RateQuantizer {
  double lsb_rad_per_s = 0.0;  // rate LSB
  // Offset each record by u * lsb, u ~ U[0, 1) drawn per record, before rounding: the unknown
  // place of a real sensor's bias on its output grid. ErrorAutocovariance averages over that
  // offset, so with it the theory is exact for a Gaussian signal; without it (offset 0) the
  // theory holds when the signal wanders over several LSBs during the record.
  bool random_offset = false;
  // Subtractive dither: rate[k] <- lsb * round(rate[k] / lsb + d_k) - lsb * d_k, d_k ~ U[-1/2, 1/2)
  // drawn per sample (ApplySubtractiveDither). random_offset is then moot.
  bool subtractive_dither = false;
  bool IsValid(std::string* why) const;
  // rate[k] <- lsb * round(rate[k] / lsb + offset_lsb).
  void Apply(std::span<double> rate_rad_per_s, double offset_lsb = 0.0) const;
  // The dithered quantizer, its dither drawn from `engine`.
  void ApplySubtractiveDither(Engine& engine, std::span<double> rate_rad_per_s) const;
  // Approximate added AVAR for busy noise: (lsb^2 / 12) / m.
  double ApproximateAvar(std::int64_t m) const;
  // Autocovariance R_e(j), j = 0..n-1, of the error e = Qz(x) - x for a Gaussian signal x of
  // (generalised) autocovariance R (n entries, rate^2), the offset on the grid uniform. The
  // sawtooth's Fourier series (Widrow & Kollar, "Quantization Noise", 2008, ch. 10, with the
  // Gaussian characteristic function of the increment x_j - x_0 of variance D(j) = 2 (R(0) - R(j))):
  //   R_e(j) = sum_{k >= 1} lsb^2 / (2 pi^2 k^2) exp(-2 pi^2 k^2 D(j) / lsb^2),  R_e(0) = lsb^2/12.
  // Under the same average e is uncorrelated with x, so the output's autocovariance is R + R_e and
  // its AVAR is AVAR_x + AvarFromAutocovariance(R_e) (docs/theory.md §1.2). When D(j) >> lsb^2 at j = 1
  // this is the white lsb^2/12 of ApproximateAvar. With subtractive dither: lsb^2/12 at lag 0,
  // 0 beyond (Schuchman's condition holds for uniform dither), for any signal.
  std::vector<double> ErrorAutocovariance(std::span<const double> signal_autocovariance) const;
};

}  // namespace allanlab::sim
