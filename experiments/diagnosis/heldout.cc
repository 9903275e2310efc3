#include "experiments/diagnosis/heldout.h"

#include <algorithm>
#include <mutex>

#include "experiments/diagnosis/baseline.h"
#include "experiments/diagnosis/candidate_estimate.h"
#include "experiments/diagnosis/refit.h"
#include "experiments/diagnosis/envelope.h"

namespace allanlab::experiments::detail {
namespace {


// The held-out half against the other half's baseline, every view, and the views in which it
// departs from that baseline beyond `threshold` (computed once per half).
const HeldoutBefore& HeldoutBaseline(const Context& ctx, int h, double threshold) {
  std::call_once(ctx.heldout_before_once[h], [&] {
    const HalfRecord& scored = ctx.halves[h];
    HeldoutBefore b;
    std::string ignored;
    const SharedFlicker flicker = RecordFlicker(ctx, h);
    b.residuals = RecordResiduals(scored.rate, scored.layout, scored.observed,
                                  ctx.spec.Model(ctx.halves[1 - h].baseline, ctx.curve.sample_clock), true,
                                  ctx.options->trials, ctx.options->seed + 500 + h, &ignored, EveryView(), &flicker,
                                  scored.other_baseline_theory.mean.empty() ? nullptr : &scored.other_baseline_theory);
    for (const GapRegion& r : FindGapRegions(b.residuals, threshold)) {
      if (std::find(b.gap_views.begin(), b.gap_views.end(), r.view) == b.gap_views.end()) b.gap_views.push_back(r.view);
    }
    ctx.heldout_before[h] = std::move(b);
  });
  return *ctx.heldout_before[h];
}

}  // namespace

GapMetrics MetricsOf(const std::vector<ViewResiduals>& residuals, const std::vector<View>& views) {
  std::vector<ViewResiduals> kept;
  for (const ViewResiduals& r : residuals) {
    if (std::find(views.begin(), views.end(), r.view) != views.end()) kept.push_back(r);
  }
  return Metrics(kept);
}

// The half a candidate is scored on: the one that holds its one-off event (a warm-up drift acts
// in the first half; a step in the half of its time), else the second (fit on the first).
int ScoredHalf(const Context& ctx, const std::vector<EffectInstance>& effects) {
  for (const EffectInstance& e : effects) {
    if (e.effect == Effect::kExponentialDrift) return 0;
    if (e.effect == Effect::kBiasStep) return e.params.at("time_s") < ctx.half_length_s ? 0 : 1;
  }
  return 1;
}


// The candidate's model for the held-out half `scored`: its stationary effects estimated, and the
// terms refitted with them, on the other half; its one-off events estimated on `scored` (falling
// back to the whole record's estimate moved to that half's clock).
bool HeldoutModel(const Context& ctx, const std::vector<EffectInstance>& effects, int scored,
                  sim::SensorModel* model, std::string* why) {
  const HalfRecord& fit_half = ctx.halves[1 - scored];
  const HalfRecord& scored_half = ctx.halves[scored];
  const sim::SensorModel probe = ctx.spec.Model(fit_half.baseline, ctx.curve.sample_clock);
  std::vector<EffectInstance> stationary, events;
  for (const EffectInstance& e : effects) {
    const bool event = IsOneOffEvent(e.effect);
    const HalfRecord& from = event ? scored_half : fit_half;
    const auto base = probe.ExpectedAvar(from.curve.m, {from.curve.num_samples, from.curve.estimator});
    EstimateInputs in{&from.curve, base, from.rate, &probe};
    in.fitted_terms = ctx.spec.terms;
    if (e.effect == Effect::kBiasStep) {  // look for it where the whole record placed it
      in.step_time_s = e.params.at("time_s") - (scored == 1 ? ctx.half_length_s : 0.0);
      in.step_block_s = ctx.half_length_s / 32.0;
    }
    std::string ignored;
    auto est = EstimateEffect(e.effect, in, &ignored);
    if (!est && event) est = ShiftEffect(e, scored == 1 ? ctx.half_length_s : 0.0);
    if (!est && !event) est = e;
    if (est) (event ? events : stationary).push_back(*est);
  }
  estimators::FitSummary fit = fit_half.baseline;
  if (!stationary.empty()) {
    sim::SensorModel ignored_model;
    if (!BestRefit(ctx.spec, fit_half.curve, fit_half.edf, fit_half.baseline, &stationary, &fit, &ignored_model, why,
                   {}, /*profile_ranges=*/false)) {
      return false;
    }
  }
  stationary.insert(stationary.end(), events.begin(), events.end());
  return WithEffects(ctx.spec.Model(fit, ctx.curve.sample_clock), stationary, model, why);
}


// The held-out half against the candidate's held-out model and against the other half's
// baseline, in the views where that half departs from the baseline (`threshold`): the score
// looks where the effect shows in the data it did not fit (spikes in the kurtosis, a step in
// the halves or the long-tau OAVAR) rather than diluting it among views it leaves alone. When no
// view of the half departs, the OAVAR score of TryCandidate stands.
void HeldoutViews(const Context& ctx, double threshold, CandidateResult* c, std::uint64_t seed) {
  const int h = c->heldout_half;
  const HalfRecord& scored = ctx.halves[h];
  if (!c->after.has_heldout || !scored.have_views || ctx.options->trials < 3) return;
  const HeldoutBefore& before = HeldoutBaseline(ctx, h, threshold);
  if (before.gap_views.empty()) return;
  std::string ignored;
  const SharedFlicker flicker = RecordFlicker(ctx, h);
  c->heldout_before = MetricsOf(before.residuals, before.gap_views);
  c->heldout_residuals = RecordResiduals(scored.rate, scored.layout, scored.observed, c->heldout_model, true,
                                         ctx.options->trials, seed, &ignored, ViewSetOf(before.gap_views), &flicker,
                                         c->heldout_theory.mean.empty() ? nullptr : &c->heldout_theory);
  c->after.heldout = MetricsOf(c->heldout_residuals, before.gap_views);
  c->heldout_in_gap_views = true;
}

GapMetrics HeldoutScore(const Context& ctx, double threshold, const sim::SensorModel& model, int h, bool gap_views,
                        std::uint64_t seed, std::vector<ViewResiduals>* residuals) {
  const HalfRecord& scored = ctx.halves[h];
  if (!gap_views) return CurveMetrics(model, scored.curve);
  std::string ignored;
  const std::vector<View>& gap = HeldoutBaseline(ctx, h, threshold).gap_views;
  const SharedFlicker flicker = RecordFlicker(ctx, h);
  std::vector<ViewResiduals> views = RecordResiduals(scored.rate, scored.layout, scored.observed, model, true,
                                                     ctx.options->trials, seed, &ignored, ViewSetOf(gap), &flicker);
  const GapMetrics metrics = MetricsOf(views, gap);
  if (residuals != nullptr) *residuals = std::move(views);
  return metrics;
}

}  // namespace allanlab::experiments::detail

namespace allanlab::experiments {

bool ScoreOnSecondRecord(const DiagnoseOptions& options, const DiagnosisSummary& summary,
                         std::span<const double> rate, SampleClock sample_clock, ValidationScores* scores, std::string* why) {
  estimators::AvarCurve curve;
  if (!RecordCurve(rate, sample_clock, &curve, why)) return false;
  const ViewLayout layout = MakeViewLayout(sample_clock, static_cast<std::int64_t>(rate.size()), curve.m);
  ViewValues observed;
  if (!ComputeViews(layout, rate, &observed, why)) return false;
  auto score = [&](sim::SensorModel model, std::uint64_t salt, std::vector<ViewResiduals>* views) -> std::optional<GapMetrics> {
    model.sample_clock = sample_clock;
    std::string ignored;
    if (!model.IsValid(&ignored)) return std::nullopt;
    *views = detail::RecordResiduals(rate, layout, observed, model, true, options.trials, options.seed + salt, &ignored);
    return detail::CurveMetrics(model, curve);
  };
  *scores = ValidationScores{};
  scores->baseline = score(summary.baseline_model, 7000, &scores->baseline_views);
  if (summary.verdict_candidate >= 0) {
    const CandidateResult& c = summary.candidates[summary.verdict_candidate];
    scores->candidate_id = c.id();
    scores->candidate = score(c.model, 7001, &scores->candidate_views);
  }
  return true;
}

}  // namespace allanlab::experiments
