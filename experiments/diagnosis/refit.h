#pragma once
// A candidate's refit: the baseline's linear terms refitted with one or more effects added (the
// effects' free parameters fitted jointly where the registry gives a fit term, effect.h), and the
// best of the ways to do it by AIC on the curve.
#include <span>
#include <string>
#include <vector>

#include "estimators/fit/avar_curve.h"
#include "estimators/fit/fit_avar_model.h"
#include "experiments/diagnosis/baseline.h"
#include "experiments/diagnosis/diagnose.h"
#include "experiments/diagnosis/effect.h"
#include "sim/sensor_model.h"

namespace allanlab::experiments::detail {

// `model` with `effects` added, into *out; false with *why when an effect does not fit the model.
bool WithEffects(sim::SensorModel model, const std::vector<EffectInstance>& effects,
                 sim::SensorModel* out, std::string* why);

// The effects added to `start` (a fit without them) by the best of the refits (see refit.cc);
// `edf`: the exact EDFs of `curve` under the start model. *effects receives the fitted
// parameters. `record_rate`: the record `curve` was computed from [rad/s] (empty in curve mode);
// when given and an effect places a deterministic path (a bias step, a warm-up drift, held at its
// estimate), the terms and the other effects are fitted to the curve of the record less that
// path instead (docs/theory.md §6.4). `profile_ranges` false: the refit's coefficient intervals
// and upper limits are left unset (for models of which only the values are read: the held-out
// half's).
bool BestRefit(const BaselineSpec& spec, const estimators::AvarCurve& curve,
               std::span<const double> edf, const estimators::FitSummary& start,
               std::vector<EffectInstance>* effects, estimators::FitSummary* fit,
               sim::SensorModel* model, std::string* why, std::span<const double> record_rate = {},
               bool profile_ranges = true);

}  // namespace allanlab::experiments::detail
