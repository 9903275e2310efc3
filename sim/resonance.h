#pragma once
// Narrowband resonance: a damped oscillator driven by white noise (second-order Gauss-Markov),
//   x'' + 2 zeta w0 x' + w0^2 x = w(t),   w0 = 2 pi f0,
// the rate noise a lightly damped mechanical mode of a MEMS gyro adds (a line of width
// ~2 zeta f0 in the PSD, e.g. near 20 Hz on the Z axis of an ADIS16405 recorded at 100 Hz).
// Parameterised by its stationary std sigma, natural frequency f0 and damping ratio zeta in (0, 1).
#include <complex>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "sim/avar_theory.h"
#include "sim/term_common.h"

namespace allanlab::sim {

struct Resonance {
  static constexpr std::string_view kId = "resonance";
  static constexpr SignalPath kPath = SignalPath::kHeld;

  double sigma_rad_per_s = 0.0;  // stationary std of the rate
  double frequency_hz = 1.0;     // natural frequency f0 (undamped)
  double damping = 0.05;         // damping ratio zeta, 0 < zeta < 1

  bool IsValid(std::string* why) const;
  // Exact point samples of the continuous process: the state (x, x') propagated by the matrix
  // exponential of the oscillator with the matching innovation covariance, started in the
  // stationary distribution. Valid at any f0, also above the sample rate's Nyquist frequency.
  void AddTo(Engine& engine, double tau0_s, std::span<double> rate_rad_per_s) const;
  // The sampled autocovariance
  //   R(k) = sigma^2 e^{-zeta w0 |k| tau0} (cos(wd k tau0) + zeta / sqrt(1 - zeta^2) sin(wd |k| tau0)),
  // wd = w0 sqrt(1 - zeta^2), at lags first_lag .. first_lag + r.size() - 1.
  void FillAutocovariance(double tau0_s, std::span<double> r, std::int64_t first_lag = 0) const;
  // Exact AVAR of the samples: R(k) = Re[c z^k] with z = e^{(-zeta w0 + i wd) tau0}, and the
  // Allan quadratic form of a geometric autocovariance sums in closed form (the AR(1) form with
  // a complex pole); O(1) per m, the lag sum where the closed form would cancel (m |1 - z| small).
  double ExpectedAvar(std::int64_t m, double tau0_s, const RecordShape& shape) const;
  // R(k) = Re[weight e^{k log_pole}] for k >= 0: weight = sigma^2 (1 - i zeta / sqrt(1 - zeta^2)),
  // log_pole = (-zeta w0 + i wd) tau0 (what sums over lags of R need in closed form).
  struct GeometricForm {
    std::complex<double> weight, log_pole;
  };
  GeometricForm Geometric(double tau0_s) const;
  // Continuous-time AVAR: the Gauss-Markov form with a complex pole l = zeta w0 - i wd,
  //   Re[c (2 l tau - 3 + 4 e^{-l tau} - e^{-2 l tau}) / (l tau)^2], c = sigma^2 (1 - i zeta/sqrt(1-zeta^2)).
  double AsymptoticAvar(double tau_s) const;
};

// AVAR(m) of a (generalised) autocovariance Re[c z^k], |z| < 1 or z -> 1, summed in closed form
// (valid for a complex pole: the geometric sums of the real AR(1) form are algebraic in z).
double GeometricAvar(std::int64_t m, std::complex<double> z, std::complex<double> c);

}  // namespace allanlab::sim
