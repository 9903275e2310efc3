#pragma once
// First-order Gauss-Markov rate noise (exponentially correlated, IEEE Std 952 "correlated noise"),
// generated as the exact discretisation of an Ornstein-Uhlenbeck process: an AR(1) sequence.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "sim/avar_theory.h"
#include "sim/term_common.h"

namespace allanlab::sim {

// Exact AVAR(m) of a stationary AR(1) y_k = phi y_{k-1} + w_k with variance `variance`
// (docs/theory.md §2.6), evaluated as the Allan quadratic form of the generalised autocovariance
// variance * (phi^j - 1), which stays accurate when phi -> 1 (the closed form cancels there).
double Ar1Avar(std::int64_t m, double phi, double variance);
// Generalised autocovariance variance * (phi^j - 1), j = first_lag..first_lag + r.size() - 1
// (a window far out costs its own length, not its distance from lag 0).
void FillAr1Autocovariance(double phi, double variance, std::span<double> r, std::int64_t first_lag = 0);
// y_k = phi y_{k-1} + w_k started in the stationary distribution; adds `std_dev`-scaled samples.
void AddAr1(Engine& engine, double phi, double std_dev, std::span<double> out);

struct GaussMarkov {
  static constexpr std::string_view kId = "gauss_markov";
  static constexpr SignalPath kPath = SignalPath::kHeld;

  double sigma_rad_per_s = 0.0;       // stationary std of the rate
  double correlation_time_s = 1.0;    // Tc

  bool IsValid(std::string* why) const;
  // Exact point samples of the OU process: phi = exp(-tau0/Tc), stationary start.
  void AddTo(Engine& engine, double tau0_s, std::span<double> rate_rad_per_s) const;
  // Lags first_lag .. first_lag + r.size() - 1.
  void FillAutocovariance(double tau0_s, std::span<double> r, std::int64_t first_lag = 0) const;
  // Exact discrete AR(1) form (docs/theory.md §2.6).
  double ExpectedAvar(std::int64_t m, double tau0_s, const RecordShape& shape) const;
  // Continuous OU: (2 sigma^2 Tc / tau) [1 - (Tc / 2tau)(3 - 4 e^{-tau/Tc} + e^{-2tau/Tc})].
  double AsymptoticAvar(double tau_s) const;
};

}  // namespace allanlab::sim
