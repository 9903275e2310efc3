#pragma once
// Held-out scores: a candidate fitted on one half of the record and scored on the other, and a
// model scored on a second recording of the same sensor.
#include <cstdint>
#include <vector>

#include "experiments/diagnosis/diagnosis_context.h"

namespace allanlab::experiments::detail {

// The half a candidate is scored on (0: first, 1: second).
int ScoredHalf(const Context& ctx, const std::vector<EffectInstance>& effects);

// The candidate's model for the held-out half `scored`.
bool HeldoutModel(const Context& ctx, const std::vector<EffectInstance>& effects, int scored,
                  sim::SensorModel* model, std::string* why);

// The held-out score of a candidate with the Monte Carlo views moved to the views in which the
// scored half departs from the other half's baseline beyond `threshold`.
void HeldoutViews(const Context& ctx, double threshold, CandidateResult* c, std::uint64_t seed);

// `model` scored on half `h`: on the views in which that half departs from the other half's
// baseline (`gap_views`, as HeldoutViews) or on OAVAR. With `residuals`, the per-view residuals
// of the gap views (left empty on OAVAR).
GapMetrics HeldoutScore(const Context& ctx, double threshold, const sim::SensorModel& model, int h, bool gap_views,
                        std::uint64_t seed, std::vector<ViewResiduals>* residuals = nullptr);

// The residuals of the views of `views` pooled.
GapMetrics MetricsOf(const std::vector<ViewResiduals>& residuals, const std::vector<View>& views);

}  // namespace allanlab::experiments::detail
