#pragma once
// Starting values of each candidate effect's parameters, read from the record (data-domain
// estimates: a spike count, a change point, a periodogram peak, a value grid, else for the angle
// quantizer the baseline's Q = lsb / sqrt(12)) or from where the
// Allan curve departs from the baseline fit (a bump -> Gauss-Markov / telegraph time constant,
// a band-limited GLS fit -> bandwidth). They are the refit's starting point, not a fit.
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "estimators/fit/avar_curve.h"
#include "estimators/fit/noise_coefficient.h"
#include "estimators/fit/parametric_term.h"
#include "experiments/diagnosis/effect.h"
#include "sim/sensor_model.h"

namespace allanlab::experiments {

struct EstimateInputs {
  const estimators::AvarCurve* curve = nullptr;   // the record's OAVAR curve (required)
  std::span<const double> baseline_avar;          // the baseline model's E[OAVAR] on the curve
  std::span<const double> rate_rad_per_s;         // the record; empty in curve mode
  const sim::SensorModel* baseline_model = nullptr;  // the fitted linear terms (bandwidth screen, Q)
  // The linear terms the candidates' refits fit (BaselineSpec::terms); empty: Q, N, B, K, R.
  // A start fitted with terms its refit will not have can win on them: a free Q took the blue
  // aliasing of a point-sampled 75 Hz filter at 100 Hz for the wrong filter family's.
  std::span<const estimators::Coefficient> fitted_terms = {};
  // Where the change-point view (block_means.h) placed a step [s from the start] and its block
  // length [s]; NaN when it saw none. The bias step's start is then looked for there.
  double step_time_s = std::numeric_limits<double>::quiet_NaN();
  double step_block_s = std::numeric_limits<double>::quiet_NaN();
};

// The fit library's band-limit term of a bandwidth effect's filter (its family, else the analog
// filter of its order, point-sampled, L = 8: effect.h AddEffect) with its cutoff kept at or above
// 1/100 of the output rate, where the term's own starting grid begins: below it the filter chain
// runs to ~5e4 L samples per evaluation and a fit that wanders there on a curve without a
// band-limit takes minutes (a 2e4-sample record: 490 s CPU).
// `start_hz` > 0 replaces the term's own starting cutoff.
std::shared_ptr<const estimators::ParametricTerm> DiagnosisBandLimitTerm(const EffectInstance& bandwidth,
                                                                         double start_hz = 0.0);

// The step of the value grid the samples sit on: the smallest gap between the distinct values of
// the first 2e5 samples, when 99 % of those values are its multiples and there are at most a
// quarter as many as samples; nullopt otherwise. An output quantizer's mark, which no filter or
// noise process leaves.
std::optional<double> RecordValueGrid(std::span<const double> rate_rad_per_s);

// Each effect's start (the registry's EffectSpec::start, effect.h): nullopt with *why when the
// record shows nothing to start from (no bump, no spike, no grid).
std::optional<EffectInstance> BandwidthStart(const EstimateInputs& in, std::string* why);
std::optional<EffectInstance> GaussMarkovStart(const EstimateInputs& in, std::string* why);
std::optional<EffectInstance> RandomTelegraphStart(const EstimateInputs& in, std::string* why);
std::optional<EffectInstance> HarmonicStart(const EstimateInputs& in, std::string* why);
std::optional<EffectInstance> AngleQuantizationStart(const EstimateInputs& in, std::string* why);
std::optional<EffectInstance> RateQuantizationStart(const EstimateInputs& in, std::string* why);
std::optional<EffectInstance> ExponentialDriftStart(const EstimateInputs& in, std::string* why);
std::optional<EffectInstance> BiasStepStart(const EstimateInputs& in, std::string* why);
std::optional<EffectInstance> OutliersStart(const EstimateInputs& in, std::string* why);
std::optional<EffectInstance> ResonanceStart(const EstimateInputs& in, std::string* why);

// The registry's start for `effect`; nullopt with *why when it has none (see above, or curve mode
// for an effect whose start reads the samples).
std::optional<EffectInstance> EstimateEffect(Effect effect, const EstimateInputs& in,
                                             std::string* why);

// The effect seen from a record that starts `offset_s` later (the held-out second half):
// a warm-up drift has decayed, a step time moves (the registry's EffectSpec::shift). nullopt when
// it no longer acts; a stationary effect is unchanged.
std::optional<EffectInstance> ShiftEffect(const EffectInstance& e, double offset_s);

}  // namespace allanlab::experiments
