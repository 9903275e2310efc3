#pragma once
// Each slow term and effect of recipe.h added to output samples y_k (k = 0 .. n-1, sample period
// tau0). Continuous-time signals enter as their exact mean over [k tau0, (k+1) tau0): what an
// integrating rate sensor reports, and a different discretization from point-sampling a discrete
// process. Every function adds to `rate` (rad/s) and draws only from `rng`.
#include <span>

#include "independent/random_stream.h"
#include "independent/recipe.h"

namespace allanlab::independent {

// Flicker by spectral synthesis: a sequence of period P = the power of two >= 4 n, with
// independent Gaussian cosine and sine amplitudes of variance a_k^2 = B^2 / (pi k) at
// frequencies k / (P tau0), k = 1 .. P/2 - 1 (the one-sided PSD B^2 / (pi f) times the bin
// width), B = floor / sqrt(2 ln 2 / pi). The first n samples are added.
void AddFlicker(double floor_rad_per_s, RandomStream& rng, std::span<double> rate);
std::int64_t FlickerPeriod(std::int64_t n);

// A Wiener rate b(t) of diffusion K^2 from b(0) = 0, averaged over each interval.
void AddRandomWalk(double k_rad_per_s_per_sqrt_s, double tau0_s, RandomStream& rng, std::span<double> rate);
// R t, averaged: R (k + 1/2) tau0.
void AddRamp(double r_rad_per_s2, double tau0_s, std::span<double> rate);
// Stationary Ornstein-Uhlenbeck process, averaged (exact joint step of state and integral).
void AddGaussMarkov(const GaussMarkov& g, double tau0_s, RandomStream& rng, std::span<double> rate);
// Continuous-time telegraph (Poisson flips, random start), averaged exactly.
void AddTelegraph(const Telegraph& t, double tau0_s, RandomStream& rng, std::span<double> rate);
// A sin(2 pi f t + phi), averaged.
void AddSinusoid(const Sinusoid& s, double tau0_s, RandomStream& rng, std::span<double> rate);
// Damped oscillator in its stationary state, point-sampled (exact 2x2 discretization).
void AddResonance(const Resonance& r, double tau0_s, RandomStream& rng, std::span<double> rate);
// s for samples k >= round(time / tau0).
void AddBiasStep(const BiasStep& b, double tau0_s, std::span<double> rate);
std::int64_t StepIndex(const BiasStep& b, double tau0_s);
// A exp(-t / tau), averaged.
void AddWarmupDrift(const WarmupDrift& d, double tau0_s, std::span<double> rate);
// Each sample carries a spike with probability rate * tau0.
void AddSpikes(const Spikes& s, double tau0_s, RandomStream& rng, std::span<double> rate);
// Replace the rate by the increments of the quantized running angle (carry kept, residual
// starting uniform in [0, q)).
void QuantizeAngle(const AngleQuantizer& q, double tau0_s, RandomStream& rng, std::span<double> rate);
// Round each sample to the LSB (with subtractive dither when asked).
void QuantizeRate(const RateQuantizer& q, RandomStream& rng, std::span<double> rate);

}  // namespace allanlab::independent
