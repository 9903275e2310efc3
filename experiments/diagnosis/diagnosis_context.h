#pragma once
// What the steps of a diagnosis (baseline.h, refit.h, heldout.h, verdict.h) share: the record, its
// curve and views, its halves, and how a model is assessed against them.
#include <cstdint>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "estimators/fit/avar_curve.h"
#include "experiments/diagnosis/baseline.h"
#include "experiments/diagnosis/diagnose.h"
#include "experiments/diagnosis/envelope.h"
#include "experiments/diagnosis/record_views.h"
#include "sim/flicker_stream_cache.h"

namespace allanlab::experiments::detail {


// One half of the record, as a fit sees it and as a held-out score reads it.
struct HalfRecord {
  estimators::AvarCurve curve;
  std::span<const double> rate;
  estimators::FitSummary baseline;  // the asked terms fitted on this half alone
  std::vector<double> edf;          // exact EDFs of `curve` under `baseline`
  OavarTheory own_baseline_theory;  // `baseline`'s exact OAVAR on `curve` (edf above is its edf)
  ViewLayout layout;
  ViewValues observed;
  bool have_views = false;
  GapMetrics against_other_baseline;  // `curve` against the other half's baseline (CurveMetrics)
  OavarTheory other_baseline_theory;  // the other half's baseline's exact OAVAR on `curve`
};


struct HeldoutBefore {
  std::vector<ViewResiduals> residuals;
  std::vector<View> gap_views;  // views with a point beyond the record's threshold
};


// Everything the candidates share.
struct Context {
  const DiagnoseOptions* options = nullptr;
  std::thread::id caller = std::this_thread::get_id();  // the thread progress is told on
  BaselineSpec spec;  // what refits fit and hold
  estimators::AvarCurve curve;
  std::vector<double> curve_edf;  // exact EDFs of `curve` under the baseline model
  std::span<const double> rate;
  ViewLayout layout;
  ViewValues observed;
  bool have_record = false;
  // Held-out halves: [0] the first, [1] the second.
  bool have_halves = false;
  HalfRecord halves[2];
  double half_length_s = 0.0;
  // Each half against the other half's baseline (computed once, by the first candidate, on any
  // thread, that needs it).
  mutable std::optional<HeldoutBefore> heldout_before[2];
  mutable std::once_flag heldout_before_once[2];
  // The flicker records the envelopes share (RecordFlicker): 480 MB for the whole record and its
  // halves at 1e6 samples and 30 trials; longer records keep what fits.
  mutable sim::FlickerStreamCache flicker_streams{std::size_t{1} << 30};
};

// The flicker record every model's envelope on the whole record (h < 0) or on half h shares per
// trial (docs/theory.md §6.1): the Kasdin synthesis, the dearest part of a simulated record, is
// done once per trial and record, not once per model. The other terms keep each envelope's seed.
SharedFlicker RecordFlicker(const Context& ctx, int h = -1);

// Tells options->progress (when set) that `stage` has `done` of `total` steps behind it; a no-op
// off the calling thread.
void ReportProgress(const Context& ctx, std::string_view stage, int done, int total);

// A record's views against a model: OAVAR and the block-mean views exact (block_means.h), the
// others from a Monte Carlo envelope when `monte_carlo` (and trials >= 3). Only the views in
// `wanted`, in View order (the others are not computed, nor simulated when none needs it).
std::vector<ViewResiduals> RecordResiduals(std::span<const double> rate, const ViewLayout& layout,
                                           const ViewValues& observed, const sim::SensorModel& model,
                                           bool monte_carlo, int trials, std::uint64_t seed,
                                           std::string* note, const ViewSet& wanted = EveryView(),
                                           const SharedFlicker* shared_flicker = nullptr,
                                           const OavarTheory* known_theory = nullptr);

// The record (or in curve mode the curve) against a model. `known_theory`: the model's
// ExactOavar on the layout when the caller has it (not computed again: O(N) per tau).
ModelGap Assess(const Context& ctx, const sim::SensorModel& model, bool monte_carlo,
                std::uint64_t seed, std::string* note, const OavarTheory* known_theory = nullptr);

// A curve against a model's exact OAVAR distribution (the exact view's z, ExactOavar).
GapMetrics CurveMetrics(const sim::SensorModel& model, const estimators::AvarCurve& curve);
// The same from the model's ExactOavar on the curve's m.
GapMetrics CurveMetrics(const OavarTheory& theory, const estimators::AvarCurve& curve);

int ParameterCount(const std::vector<EffectInstance>& effects);
bool ClosesGap(const ModelGap& gap, double threshold);
// chi2 over the views with an exact distribution (OAVAR and the block-mean views), which every
// assessment has: what a candidate's first score compares (docs/theory.md §6.4).
double ExactChi2(const ModelGap& gap);

// One candidate (one or more effects from their starts): refitted, assessed on the exact OAVAR
// view, scored, and held out.
std::optional<CandidateResult> TryCandidate(const Context& ctx, const DiagnosisSummary& s,
                                            const std::vector<EffectInstance>& effects,
                                            std::string* why);

}  // namespace allanlab::experiments::detail
