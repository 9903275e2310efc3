#pragma once
// Sim-to-real gap diagnosis (docs/theory.md §6): where a recording departs from its fitted IEEE 952 model,
// which unmodelled effect (effect.h) explains it, and how far the gap shrinks once it is added.
//
// 1. Baseline: GLS fit of the asked terms (estimators/fit/fit_avar_model.h) on the record's
//    overlapping Allan curve (10 taus per decade).
// 2. Views and envelopes (record_views.h, envelope.h): OAVAR against its exact distribution,
//    the other views against `trials` simulated records of the fitted model.
// 3. Where: standardised residuals and gap regions with Bonferroni control over every point of
//    every view (gap.h): a record drawn from the model is flagged with probability <= alpha.
// 4. Which: for each effect with a starting value (candidate_estimate.h), the model is refitted
//    with the effect and the gap re-measured. Effects that are fit-library terms (gauss_markov,
//    random_telegraph, harmonic, bandwidth: estimators/fit/parametric_term.h) are fitted jointly
//    with the linear terms by GLS (parametric_fit.h), started at the estimate (correlation times
//    also at 1/3 and 3 x, lowest chi2 kept); the others keep their estimate and the linear terms
//    are refitted on the curve corrected by E[linear] / E[linear + effect] (three passes). Ranked by the
//    penalised improvement score = chi2_before - chi2_after - 2 k (k the effect's parameters,
//    AIC with -2 ln L ~ sum z^2), exact OAVAR view; the best `envelope_candidates` also get the
//    Monte Carlo views (those already beyond the threshold on their exact views only when no
//    candidate is acceptable without them: monte_carlo_deferred). Held-out: the same refit on one half, scored on the other (the half
//    holding a one-off event such as a step, which is located there; else the second half), on
//    OAVAR and, for the candidates with Monte Carlo views, on the views in which that half
//    departs from the other half's baseline.
//    When no single effect closes the gap, a set of up to `max_effects` is grown by forward
//    selection on the held-out score (verdict.cc GrowSet, docs/theory.md §6.4): each added
//    effect must shrink the held-out chi2, and the chi2 of a view it shows in that still
//    departs, by `set_margin`, and move no view beyond the threshold.
//    Allan-equivalent effects (telegraph / Gauss-Markov) that both pass are decided by the view
//    that separates them (kurtosis: lower chi2 wins); the other is listed as also consistent.
// 5. Verdict: "none" (no significant gap), the effect (or set) that closes the gap (every view
//    within the threshold) with a positive score and a held-out improvement; of candidates
//    within 2 of the best penalised score (which the record cannot tell apart), the one with the
//    largest held-out shrink. Else the one that explains most of it (explains_all false): held-out
//    chi2 and the chi2 summed over the views where the baseline departs down by `partial_shrink`
//    (each of them at least halved), what remains listed (`remaining`). Else "unexplained".
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/sample_clock.h"
#include "estimators/fit/avar_curve.h"
#include "estimators/fit/fit_avar_model.h"
#include "experiments/diagnosis/effect.h"
#include "experiments/diagnosis/envelope.h"
#include "experiments/diagnosis/gap.h"
#include "experiments/diagnosis/line_drift.h"
#include "sim/sensor_model.h"

namespace allanlab::experiments {

struct DiagnoseOptions {
  // What the record is measured against.
  //   kTerms:  the IEEE terms in `terms` fitted to the curve (GLS), nothing else;
  //   kFit:    what `allanlab fit` reports by default: those terms plus a band-limit when the
  //            curve shows one (estimators/fit/band_limited_fit.h), its cutoff then held;
  //   kSensor: `sensor` as given (its coefficients, band-limit, quantizers and every term held),
  //            only the IEEE terms listed in `terms` (may be empty) refitted.
  enum class Baseline { kTerms, kFit, kSensor };
  Baseline baseline = Baseline::kTerms;
  sim::SensorModel sensor;  // kSensor: the user's simulation model (its rate is the record's)
  std::vector<estimators::Coefficient> terms = {
      estimators::Coefficient::kQ, estimators::Coefficient::kN, estimators::Coefficient::kB,
      estimators::Coefficient::kK, estimators::Coefficient::kR};
  double false_alarm = 0.05;  // alpha: chance that a record of the model itself is flagged
  int trials = 30;            // simulated records per Monte Carlo envelope (>= 3; 0: OAVAR only)
  std::uint64_t seed = 1;     // of the simulated records
  int envelope_candidates = 3;  // best candidates that also get the Monte Carlo views
  // Leave the Monte Carlo views of candidates already beyond the threshold on their exact views
  // until no candidate is acceptable without them (CandidateResult::monte_carlo_deferred); the
  // verdict is the same either way. false: simulate them at once (the tests compare the two).
  bool defer_envelopes = true;
  int max_effects = 3;        // members of a set verdict (1: single effects only)
  double set_margin = 0.2;    // relative chi2 drop an added member must bring (see GrowSet)
  double partial_shrink = 5.0;  // held-out and departing views' chi2 shrink naming a partial verdict
  std::vector<Effect> effects = {std::begin(kAllEffects), std::end(kAllEffects)};
  // Told as the diagnosis advances: the stage ("baseline", "views", "candidates", "Monte Carlo
  // views", "sets of 2", "sets of 2: Monte Carlo views", ...), and how many of its steps are done
  // of `total` (0: one step). Called from the calling thread only; empty: silent. Changes nothing
  // in the result.
  std::function<void(std::string_view stage, int done, int total)> progress;
  bool IsValid(std::string* why) const;
};

// One model against the record.
struct ModelGap {
  std::vector<ViewResiduals> views;
  bool has_heldout = false;
  GapMetrics heldout;  // OAVAR of the second half against the model fitted on the first half
  GapMetrics View(View v) const;  // zero points when the view is absent
  GapMetrics All() const { return Metrics(views); }
};

struct CandidateResult {
  std::vector<EffectInstance> effects;  // one, or two for a pair
  estimators::FitSummary fit;           // the linear terms refitted with the effect
  sim::SensorModel model;
  // The exact OAVAR of `model` on the record and of `heldout_model` on the scored half, kept for
  // the views, the held-out score and the plot that read them again (each costs O(N) per tau).
  OavarTheory theory, heldout_theory;
  ModelGap after;
  // Held-out: the candidate fitted on one half and scored on the other (after.heldout), against
  // the other half's baseline scored the same way (heldout_before). The scored half is the one
  // holding a one-off event (bias_step, exponential_drift: located on it, their noise terms from
  // the other half), else the second. Scored on OAVAR; once full_views, on the views in which
  // the scored half departs from the other half's baseline beyond the record's threshold (a
  // spike shows in the kurtosis, not in the Allan variance), when there are any.
  GapMetrics heldout_before;
  int heldout_half = 1;            // 0: first half scored, 1: second
  sim::SensorModel heldout_model;  // the model scored on that half
  bool heldout_in_gap_views = false;
  std::vector<ViewResiduals> heldout_residuals;  // per view of after.heldout, when heldout_in_gap_views
  double score = 0.0;            // OAVAR chi2 improvement - 2 k
  double full_score = 0.0;       // all assessed views: chi2 improvement - 2 k
  bool full_views = false;       // Monte Carlo views assessed
  bool closes_gap = false;       // every assessed |z| <= threshold
  // Due the Monte Carlo views but already beyond the threshold on its exact views (OAVAR,
  // change_point, trend), so never acceptable: left without them because another candidate was
  // acceptable (they are simulated when none is, for a partial verdict or a set).
  bool monte_carlo_deferred = false;
  // What each member added, in the order forward selection took them: the held-out chi2 before
  // (the baseline, then the set so far, scored on this candidate's half and views) and after.
  struct Step {
    Effect added;
    GapMetrics heldout_before, heldout_after;
    // The same in the held-out views the added effect shows in (the registry's views), where a
    // later member was judged there (points 0: not read; set_rules.h EarnsItsPlace).
    GapMetrics own_views_before, own_views_after;
  };
  std::vector<Step> steps;
  // Why it is not the verdict, in words with its numbers (empty for the verdict; for
  // "unexplained" every candidate says why it was not named): the first rule of the verdict
  // (5. above) it fails, or the candidate that won and on what.
  std::string why_not_verdict;
  std::string id() const;        // "gauss_markov" or "bias_step+outliers"
};

struct SkippedEffect {
  Effect effect;
  std::string reason;
};

struct AlsoConsistent {
  std::string effect;
  std::string separating_view;  // a view that could tell it from the verdict ("" when none known)
};

// The record's rate level over time, as the block-mean views see it (block_means.h), for a plot:
// the means of `blocks` equal blocks of floor(N / blocks) samples, and each model's deterministic
// path (its bias steps and warm-up drifts; zero without them) averaged over the same blocks. The
// models' constant level (the bias, which no view tests) is left out of the paths.
struct BlockMeanSeries {
  double block_s = 0.0;
  std::vector<double> time_s;         // block centres [s from the start]
  std::vector<double> record;         // [rad/s]
  std::vector<double> baseline_path;  // [rad/s]
  std::vector<double> verdict_path;   // [rad/s]; empty without a verdict's (or best tried) model
  // Each model's standard deviation of a block mean about the mean of all blocks (so a 95 % band
  // is the path, set to the record's mean, +- 1.96 of it: BlockMeanDeviationSd, block_means.h).
  std::vector<double> baseline_sd;  // [rad/s]
  std::vector<double> verdict_sd;   // [rad/s]; empty without a verdict's (or best tried) model
};

struct DiagnosisSummary {
  bool ok = false;
  std::string message;
  bool curve_mode = false;
  std::int64_t num_samples = 0;
  SampleClock sample_clock;
  estimators::AvarCurve curve;
  estimators::FitSummary baseline;
  sim::SensorModel baseline_model;
  DiagnoseOptions::Baseline baseline_source = DiagnoseOptions::Baseline::kTerms;  // options.baseline
  OavarTheory baseline_theory;  // the baseline's exact OAVAR on the record (as theory above)
  ModelGap before;
  int total_points = 0;
  double threshold = 0.0;  // |z| level of a gap (Bonferroni over total_points)
  bool significant = false;
  std::vector<GapRegion> regions;
  std::vector<CandidateResult> candidates;  // best first
  std::vector<SkippedEffect> skipped;
  std::string verdict;  // "none", an effect id or set ("a+b"), or "unexplained"
  bool explains_all = true;  // false: the verdict explains most of the gap, not all (see 5. above)
  std::vector<GapRegion> remaining;  // the verdict's (or best tried) model against the record
  int verdict_candidate = -1;  // index into candidates (also for "unexplained": the best tried)
  std::vector<AlsoConsistent> also_consistent;
  std::vector<std::string> notes;  // fallbacks taken
  BlockMeanSeries block_means;     // empty in curve mode
  // When a harmonic and a resonance both close the gap: the share of the line's power in the
  // whole record's periodogram main lobe (line_shape.h), which chose between them; NaN otherwise.
  double line_lobe_share = std::numeric_limits<double>::quiet_NaN();
  // The spectral line a resonance or harmonic candidate was fitted to (the verdict's or best
  // tried model's when it has one, else the best scoring such candidate's), measured along the
  // record (line_drift.h); nullopt in curve mode, without such a candidate, or where it cannot be
  // measured.
  std::optional<LineDrift> line_drift;
  double line_drift_frequency_hz = std::numeric_limits<double>::quiet_NaN();  // the line measured
  // When an output quantizer won the verdict because the samples sit on its value grid: the grid's
  // step (rad/s); NaN otherwise.
  double value_grid_rad_per_s = std::numeric_limits<double>::quiet_NaN();
};

// A record of rate samples (rad/s) on its sample clock. Returns summary->ok (false: bad options, a
// record too short for the views, a failed baseline fit, with the reason in message).
bool DiagnoseRecord(const DiagnoseOptions& options, std::span<const double> rate_rad_per_s,
                    SampleClock sample_clock, DiagnosisSummary* summary);

// A published curve only (no record): the OAVAR view alone, candidates estimable from the curve
// (bandwidth, gauss_markov, random_telegraph), no held-out score. curve.num_samples must be set.
bool DiagnoseCurve(const DiagnoseOptions& options, const estimators::AvarCurve& curve,
                   DiagnosisSummary* summary);

// A diagnosis' models scored on a second recording of the same sensor (`--validate-on`): the
// exact OAVAR view of that record's curve against the baseline and against the verdict's model
// (or, for "unexplained", the best tried), each with its sample rate set to the second record's.
// A model invalid at that rate has no score (nullopt).
struct ValidationScores {
  std::optional<GapMetrics> baseline;
  std::string candidate_id;  // empty when the diagnosis has no candidate
  std::optional<GapMetrics> candidate;
  // Every view of the second record (OAVAR exact, the others against `trials` simulated records
  // of each model): baseline and candidate, view by view (empty when a model has no score).
  std::vector<ViewResiduals> baseline_views, candidate_views;
};
// False with *why when the second record gives no usable curve.
// `options` gives the Monte Carlo views' trials and seed (trials 0: OAVAR only).
bool ScoreOnSecondRecord(const DiagnoseOptions& options, const DiagnosisSummary& summary,
                         std::span<const double> rate_rad_per_s, SampleClock sample_clock,
                         ValidationScores* scores, std::string* why);

// The record's overlapping Allan curve on 10 taus per decade with Greenhall-Riley EDFs
// (positive values only), as the baseline fit uses it.
bool RecordCurve(std::span<const double> rate_rad_per_s, SampleClock sample_clock,
                 estimators::AvarCurve* curve, std::string* why);

}  // namespace allanlab::experiments
