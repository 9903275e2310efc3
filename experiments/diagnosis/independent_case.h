#pragma once
// One recording of the diagnosis benchmark drawn from the independent generator
// (independent/recipe.h), which shares no code with sim/ nor with the diagnosis candidates: other
// discretizations (continuous-time terms averaged over each sample), other filter designs
// (impulse-invariant and bilinear, first and second order, CIC), random biases and phases,
// heavy-tailed and one-sided spikes, quantizers with random bias and dither.
//
// Layout (deterministic in seed and index): recording i is a control when
// floor((i + 1) c) > floor(i c) for the control fraction c (so any prefix holds the fraction),
// otherwise the next effect in turn (bandwidth, gauss_markov, random_telegraph, harmonic,
// angle_quantization, rate_quantization, exponential_drift, bias_step, outliers, and resonance when
// the diagnosis knows that id); every fourth round of effects is borderline, the others clear.
// The sensor: N, B (as its flicker ADEV floor) and K drawn log-uniform over MEMS ranges, a random
// bias, at the given rate and length. The user's model handed to diagnose: `--model N,B,K`.
//
// Strength, one scale for every effect (computed here from independent/allan_forms.h, not from
// sim/): the largest of
//   oavar:  max over tau of |ln(E_full / E_fit)| sqrt(nu / 2), E_fit the nonnegative weighted
//           least-squares fit of N^2/tau + floor^2 + K^2 tau/3 to E_full (the share of the effect
//           the user's model absorbs is not a gap), nu = 0.75 N/m (a lower bound of the
//           overlapping EDF across white to random-walk noise);
//   kurtosis (outliers, quantizers): expected excess kurtosis of the first differences over its
//           null sd sqrt(24/N) (spikes of Pareto magnitude: 2 p E[a^4]; uniform quantization
//           error: -1.2 (q^2/12)^2 entering two differences, 18 for an angle LSB);
//   block (bias_step, exponential_drift): the effect's change between two adjacent block means
//           over the block's own Allan deviation: a step s at t: |s| / (sqrt 2 ADEV(min(t, T - t)));
//           a drift A e^{-t/tau}: the first two blocks of length tau differ by A (1 - 1/e)^2, over
//           sqrt 2 ADEV(tau).
// Classes: borderline z in [3, 10), clear z in [10, 60] (drawn log-uniform, the strength
// parameter solved for by bisection); effects whose strength cannot reach the class keep what
// the parameter range allows and are classed by what they achieve.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "experiments/diagnosis/benchmark_case.h"
#include "independent/recipe.h"

namespace allanlab::experiments {

struct IndependentDrawOptions {
  double rate_hz = 100.0;
  double min_duration_s = 1800.0, max_duration_s = 3600.0;  // log-uniform
  double control_fraction = 0.45;
  bool with_resonance = false;  // the diagnosis knows the id "resonance"
  bool IsValid(std::string* why) const;
};

struct IndependentCase {
  independent::Recipe recipe;  // base + effect
  independent::Recipe base;    // the sensor without the effect
  std::int64_t num_samples = 0;
  std::string effect_id;       // diagnosis effect id, "" for a control
  std::string design;          // which variant of the effect family (e.g. "lp2_bilinear_average")
  // The descriptor the scoring reads (benchmark_score.h): preset = "independent", effect with
  // the independent parameters, strengths, per-tau gap z.
  BenchmarkCase descriptor;
};

// The effects in their turn order (resonance only when asked).
std::vector<std::string> IndependentEffectOrder(bool with_resonance);

bool DrawIndependentCase(const IndependentDrawOptions& options, std::uint64_t seed, int index,
                         IndependentCase* c, std::string* why);

// A real recording with one effect injected (independent::Inject): `segment` (rad/s at
// `rate_hz`) plays the base, and the effect's strength is solved, clear (z in [10, 60]), against
// the segment's own overlapping AVAR on the same grid in place of a base model (the oavar view
// compares base + effect with that curve itself, not with a refit: a real curve fits no IEEE
// model, so only the change the effect makes is its strength). The effects
// that can be added to a recording after the fact, in turn (index % 6): bias_step,
// exponential_drift, outliers, harmonic, gauss_markov, random_telegraph. *record receives the
// segment with the effect. `source` names the segment in the table (preset column).
bool DrawInjectedCase(std::span<const double> segment, double rate_hz, const std::string& source,
                      std::uint64_t seed, int index, IndependentCase* c, std::vector<double>* record,
                      std::string* why);
inline constexpr int kInjectedEffects = 6;

// The strength of `full` over `base` for n samples (fills the strength fields, tau_s and gap_z of
// *d; `effect_id` says which views apply). Exposed for tests and for injected real recordings.
void MeasureIndependentStrength(const independent::Recipe& base, const independent::Recipe& full,
                                const std::string& effect_id, std::int64_t n, BenchmarkCase* d);

}  // namespace allanlab::experiments
