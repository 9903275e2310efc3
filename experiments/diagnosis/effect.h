#pragma once
// The fixed vocabulary of unmodelled effects `allanlab diagnose` can name (ids are part of
// the JSON output: stable; add, never rename, docs/architecture.md), and how each one is added to a sensor
// model so that sim/ generates it and knows its exact expected Allan variance.
//
// Parameters are SI with the unit in the name (JSON keys are these names):
//   bandwidth           cutoff_hz, order (1: RC, 2: Butterworth)
//   gauss_markov        sigma_rad_per_s, correlation_time_s
//   random_telegraph    amplitude_rad_per_s, mean_dwell_s
//   harmonic            amplitude_rad_per_s, frequency_hz
//   angle_quantization  lsb_rad
//   rate_quantization   lsb_rad_per_s
//   exponential_drift   amplitude_rad_per_s, time_constant_s
//   bias_step           size_rad_per_s, time_s
//   outliers            rate_hz, size_rad_per_s
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "sim/sensor_model.h"

namespace allanlab::experiments {

enum class Effect {
  kBandwidth,
  kGaussMarkov,
  kRandomTelegraph,
  kHarmonic,
  kAngleQuantization,
  kRateQuantization,
  kExponentialDrift,
  kBiasStep,
  kOutliers,
};
inline constexpr Effect kAllEffects[] = {
    Effect::kBandwidth,         Effect::kGaussMarkov,      Effect::kRandomTelegraph,
    Effect::kHarmonic,          Effect::kAngleQuantization, Effect::kRateQuantization,
    Effect::kExponentialDrift,  Effect::kBiasStep,          Effect::kOutliers};

std::string_view EffectId(Effect e);
bool ParseEffect(std::string_view id, Effect* e);
// Names of the effect's parameters, in the order above.
std::vector<std::string> EffectParameterNames(Effect e);

// One effect with its parameter values (keys from EffectParameterNames).
struct EffectInstance {
  Effect effect = Effect::kGaussMarkov;
  std::map<std::string, double> params;
  // Every parameter present, finite, and in its domain for a record at `sample_rate_hz`.
  bool IsValid(double sample_rate_hz, std::string* why) const;
};

// `model` with the effect added (a term, the band-limit or an output quantizer). Returns false
// with *why when the effect does not fit the model (invalid parameters, a second band-limit).
bool AddEffect(const EffectInstance& effect, sim::SensorModel* model, std::string* why);

// Effects whose Allan variance is identical for matching parameters, so no Allan-family view
// can tell them apart, and the view that can (empty when none is known).
struct Indistinguishable {
  Effect other;
  std::string separating_view;
};
std::vector<Indistinguishable> AllanEquivalents(Effect e);

}  // namespace allanlab::experiments
