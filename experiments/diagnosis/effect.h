#pragma once
// The unmodelled effects `allanlab diagnose` can name, in one registry: for each effect its stable
// id (JSON and CLI; add, never rename), its parameters, how sim/ generates it (added to a sensor
// model, which then knows its exact expected Allan variance), where a candidate starts
// (candidate_estimate.h), the fit library term that refits it (estimators/fit/parametric_term.h)
// and the views it shows in. Adding an effect is one row in effect.cc plus its generator, start
// and (optionally) fit term.
//
// Parameters are SI with the unit in the name (JSON keys are these names):
//   bandwidth           cutoff_hz, order (1: RC, 2: Butterworth); optional family (index into
//                       sim::BandLimitFamilies(): moving_average, digital2_bilinear, ...; without
//                       it the analog filter of that order, point-sampled, L = 8)
//   gauss_markov        sigma_rad_per_s, correlation_time_s
//   random_telegraph    amplitude_rad_per_s, mean_dwell_s
//   harmonic            amplitude_rad_per_s, frequency_hz
//   angle_quantization  lsb_rad
//   rate_quantization   lsb_rad_per_s; optional subtractive_dither (1: the error uniform and
//                       independent of the signal, the samples on no grid; 0 or absent: rounding)
//   exponential_drift   amplitude_rad_per_s, time_constant_s
//   bias_step           size_rad_per_s, time_s
//   outliers            rate_hz, size_rad_per_s
//   resonance           sigma_rad_per_s, frequency_hz, damping
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "experiments/diagnosis/record_views.h"
#include "sim/sensor_model.h"

namespace allanlab::estimators {
class ParametricTerm;
}

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
  kResonance,
};
inline constexpr Effect kAllEffects[] = {
    Effect::kBandwidth,         Effect::kGaussMarkov,      Effect::kRandomTelegraph,
    Effect::kHarmonic,          Effect::kAngleQuantization, Effect::kRateQuantization,
    Effect::kExponentialDrift,  Effect::kBiasStep,          Effect::kOutliers,
    Effect::kResonance};

// One effect with its parameter values (keys: the effect's parameter names).
struct EffectInstance {
  Effect effect = Effect::kGaussMarkov;
  std::map<std::string, double> params;
  // Every parameter present, finite, and in its domain for a record at `sample_rate_hz`.
  bool IsValid(double sample_rate_hz, std::string* why) const;
};

// A random telegraph's start read off the record's two levels (candidate_estimate.h) carries this
// parameter besides its own: how many standard deviations of the block means apart the two levels
// lie.
inline constexpr std::string_view kLevelSeparationParam = "level_separation_sd";
// An effect whose start the record measures better than the Allan curve can: held at it in the
// joint fit of its refits, as a step is, instead of freed. So far a telegraph whose two levels the
// record shows: the Allan curve alone trades its amplitude and dwell for B and K (an independent
// 145 deg/h telegraph of 35 s dwell fitted as 109 deg/h and 24 s beside a large K),
// which the kurtosis view then rejects.
bool HeldAtItsStart(const EffectInstance& e);

struct EstimateInputs;  // candidate_estimate.h

// How a candidate's refit treats the effect when no fit term frees its parameters.
enum class HeldRefit {
  kJointFit,     // held at its start inside the joint GLS fit (an additive term the linear terms
                 // must not absorb: spikes, a step, a warm-up drift)
  kSubtractive,  // the linear terms refitted to the curve minus its AVAR (an output quantizer,
                 // whose error is uncorrelated with the signal)
  kRatio,        // the linear terms refitted to the curve scaled by E[without] / E[with]
};

// Effects with the same Allan variance for matching parameters (no Allan-family view tells them
// apart), and the view that can (empty when none is known).
struct Indistinguishable {
  Effect other;
  std::string separating_view;
};

struct EffectSpec {
  Effect effect;
  std::string_view id;
  std::vector<std::string> params;  // SI names; a fit term's parameters are the first ones, in order
  // The generator: `model` with the effect added (a term, the band-limit or an output quantizer);
  // false with *why for invalid parameters or a model the effect cannot join.
  bool (*add)(const EffectInstance& effect, sim::SensorModel* model, std::string* why);
  // The candidate's starting value from the record (or its curve); nullopt with *why when the
  // record shows nothing to start from.
  std::optional<EffectInstance> (*start)(const EstimateInputs& in, std::string* why);
  bool needs_record;  // the start reads the samples (no candidate in curve mode)
  // The fit library term that refits the effect's free parameters jointly with the linear terms;
  // nullptr: the effect is held at its start (`held`).
  std::shared_ptr<const estimators::ParametricTerm> (*fit_term)(const EffectInstance& effect);
  HeldRefit held;
  // A one-off event (a step, a warm-up drift): the effect seen from a record starting offset_s
  // later (nullopt when it no longer acts there); nullptr for a stationary effect.
  std::optional<EffectInstance> (*shift)(const EffectInstance& effect, double offset_s);
  std::vector<View> views;  // the views in which it shows
  std::vector<Indistinguishable> allan_equivalents;
};

// Every effect, in kAllEffects order.
const std::vector<EffectSpec>& EffectRegistry();
const EffectSpec& SpecOf(Effect e);

std::string_view EffectId(Effect e);
bool ParseEffect(std::string_view id, Effect* e);
std::vector<std::string> EffectParameterNames(Effect e);
// A band-limit's filter family (sim::BandLimitFamilies() name: "moving_average", "analog1_point",
// ...); empty for other effects.
std::string FilterFamilyName(const EffectInstance& effect);
// A rate quantizer with subtractive dither.
bool HasSubtractiveDither(const EffectInstance& effect);
// Which member of its effect's family: a band-limit's filter family, "subtractive dither" for a
// dithered quantizer; empty otherwise.
std::string EffectVariant(const EffectInstance& effect);
// The effect's name as a report gives it: the id and its variant in parentheses
// ("bandwidth (moving_average)", "rate_quantization (subtractive dither)").
std::string EffectLabel(const EffectInstance& effect);
bool AddEffect(const EffectInstance& effect, sim::SensorModel* model, std::string* why);
bool IsOneOffEvent(Effect e);
std::vector<Indistinguishable> AllanEquivalents(Effect e);

}  // namespace allanlab::experiments
