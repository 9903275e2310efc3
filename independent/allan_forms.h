#pragma once
// Expected overlapping Allan variance of what generate.h makes, derived here from each
// component's own definition (recipe.h), not taken from sim/. AVAR(m) is in (rad/s)^2 at
// tau = m tau0 for a record of n samples; E[OAVAR] = AVAR for every stationary component, and
// the deterministic ones (ramp, step, drift) enter with their exact OAVAR on n samples.
//
// Exact for every m (given the discretization of recipe.h):
//   white N, any law:      N^2 / tau                       (no low-pass)
//   white through a chain: from the chain's output autocovariance (low_pass_chain.h)
//   flicker:               sum_k a_k^2 2 sin^4(pi k m / P) / (m^2 sin^2(pi k / P)), a_k^2 = B^2/(pi k)
//                          (IEEE 952: -> 2 ln2 B^2 / pi = floor^2 for 1 << m << P)
//   rate random walk:      K^2 tau / 3        (continuous averages: the IEEE 952 form is exact)
//   ramp:                  R^2 tau^2 / 2
//   Gauss-Markov:          s^2 Tc^2 / tau^2 (2 tau / Tc - 3 + 4 e^{-tau/Tc} - e^{-2 tau/Tc})
//   telegraph:             the same with s = a, Tc = dwell / 2 (autocovariance a^2 e^{-2|t|/dwell})
//   sinusoid (random phase): A^2 sin^4(pi f tau) / (pi f tau)^2
//   resonance:             from R(t) = s^2 e^{-a|t|} (cos wd t + a/wd sin wd|t|), a = zeta w0
//   bias step s at sample j: (1 / (2 (n - 2m + 1))) sum over the differences straddling j
//                          (interior step: s^2 (2 m^2 + 1) / (6 m (n - 2m + 1)) ~ s^2 tau / (3 T))
//   warm-up drift:         geometric sum, A^2 d^2 (1 - e^{-m x})^4 (1 - r^M) / (2 M m^2 x^2 (1 - r)),
//                          x = tau0 / tau_d, d = 1, r = e^{-2x}, M = n - 2m + 1
//   spikes:                p E[a^2] / m (two-sided), (p E[a^2] - p^2 E[a]^2) / m (one-sided)
//   rate quantizer with subtractive dither: q^2 / (12 m)
// Approximate (flagged by ExpectedOavarIsExact):
//   rate quantizer without dither: q^2 / (12 m) (Sheppard: noise spanning several LSBs);
//   angle quantizer: q^2 / (4 tau^2) (IEEE 952 Q = q / sqrt 12; the angle crossing many LSBs).
#include <cstdint>
#include <span>
#include <vector>

#include "independent/recipe.h"

namespace allanlab::independent {

double ExpectedOavar(const Recipe& recipe, std::int64_t m, std::int64_t n);
std::vector<double> ExpectedOavar(const Recipe& recipe, std::span<const std::int64_t> ms, std::int64_t n);
bool ExpectedOavarIsExact(const Recipe& recipe);

// AVAR(m) of a stationary sequence with autocovariance r[0..]: (1/m^2) sum_{|j|<m} (m - |j|)
// (R_j - R_{j+m}); r must hold lags up to 2m - 1 (zero beyond its end).
double AvarFromAutocovariance(std::span<const double> r, std::int64_t m);

// The components one by one (tau in s, rates in rad/s), for tests and strength estimates.
double GaussMarkovAvar(double sigma, double correlation_time_s, double tau_s);
double SinusoidAvar(double amplitude, double frequency_hz, double tau_s);
double FlickerAvar(double floor_rad_per_s, std::int64_t m, std::int64_t n);
double BiasStepOavar(double size, std::int64_t step_index, std::int64_t m, std::int64_t n);
double WarmupDriftOavar(double amplitude, double time_constant_s, double tau0_s, std::int64_t m, std::int64_t n);
double ResonanceAvar(const Resonance& r, double tau0_s, std::int64_t m);
double SpikesAvar(const Spikes& s, double tau0_s, std::int64_t m);
double WhiteChainAvar(const Recipe& recipe, std::int64_t m);  // white noise through the recipe's chain

}  // namespace allanlab::independent
