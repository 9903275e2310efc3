#pragma once
// Starting values of each candidate effect's parameters, read from the record (data-domain
// estimates: a spike count, a change point, a periodogram peak, a value grid) or from where the
// Allan curve departs from the baseline fit (a bump -> Gauss-Markov / telegraph time constant,
// the short-tau inflection -> bandwidth). They are the refit's starting point, not a fit.
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "estimators/fit/avar_curve.h"
#include "experiments/diagnosis/effect.h"

namespace allanlab::experiments {

struct EstimateInputs {
  const estimators::AvarCurve* curve = nullptr;   // the record's OAVAR curve (required)
  std::span<const double> baseline_avar;          // the baseline model's E[OAVAR] on the curve
  std::span<const double> rate_rad_per_s;         // the record; empty in curve mode
};

// nullopt with *why when the effect has no starting value (no bump, no spike, no grid, curve
// mode for a data-domain effect).
std::optional<EffectInstance> EstimateEffect(Effect effect, const EstimateInputs& in,
                                             std::string* why);

// The effect seen from a record that starts `offset_s` later (the held-out second half):
// a warm-up drift has decayed, a step time moves. nullopt when it no longer acts.
std::optional<EffectInstance> ShiftEffect(const EffectInstance& e, double offset_s);

}  // namespace allanlab::experiments
