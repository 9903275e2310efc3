#include "experiments/diagnosis/verdict.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <optional>

#include "common/number_text.h"
#include "estimators/fit/noise_coefficient.h"
#include "experiments/diagnosis/block_means.h"
#include "experiments/diagnosis/candidate_estimate.h"
#include "experiments/diagnosis/gaussian_views.h"
#include "experiments/diagnosis/heldout.h"
#include "experiments/diagnosis/line_drift.h"
#include "experiments/diagnosis/line_shape.h"
#include "experiments/diagnosis/set_rules.h"
#include "experiments/diagnosis/warmup_drift_views.h"

namespace allanlab::experiments::detail {
namespace {

using estimators::Coefficient;

bool ByScore(const CandidateResult& a, const CandidateResult& b) { return a.score > b.score; }

// Each effect's candidate from its start, refitted and scored on the exact views, best
// first; effects without a start (or whose refit fails) are listed as skipped. The effects are
// independent, so they run in parallel; results are kept in effect order, so the outcome is the
// same for any thread count.
void RankSingles(const Context& ctx, DiagnosisSummary* s) {
  const std::vector<Effect>& effects = ctx.options->effects;
  const int n = static_cast<int>(effects.size());
  std::vector<std::optional<CandidateResult>> results(n);
  std::vector<std::string> reasons(n);
  const auto base = s->baseline_model.ExpectedAvar(ctx.curve.m, {ctx.curve.num_samples, ctx.curve.estimator});
  EstimateInputs in{&ctx.curve, base, ctx.rate, &s->baseline_model};
  in.fitted_terms = ctx.spec.terms;
  LocatedStep(s->before.views, s->threshold, &in.step_time_s, &in.step_block_s);
  std::atomic<int> done{0};
  ReportProgress(ctx, "candidates", 0, n);
#pragma omp parallel for schedule(dynamic, 1)
  for (int i = 0; i < n; ++i) {
    if (const auto est = EstimateEffect(effects[i], in, &reasons[i])) results[i] = TryCandidate(ctx, *s, {*est}, &reasons[i]);
    ReportProgress(ctx, "candidates", done.fetch_add(1) + 1, n);
  }
  for (int i = 0; i < n; ++i) {
    if (results[i]) {
      s->candidates.push_back(std::move(*results[i]));
    } else {
      s->skipped.push_back({effects[i], reasons[i]});
    }
  }
  std::stable_sort(s->candidates.begin(), s->candidates.end(), ByScore);
}

// The candidate against every view (Monte Carlo ones included) and its held-out score moved to the
// views in which the held-out half departs.
void FullAssess(const Context& ctx, const DiagnosisSummary& s, CandidateResult* c, std::uint64_t salt) {
  std::string note;
  ModelGap full;
  if (ctx.have_record) {
    // The exact views are those TryCandidate assessed the same model on: only the Monte Carlo
    // ones are new. Kept in View order, as Assess gives them.
    const SharedFlicker flicker = RecordFlicker(ctx);
    full.views = RecordResiduals(ctx.rate, ctx.layout, ctx.observed, c->model, true, ctx.options->trials,
                                 ctx.options->seed + salt, &note, MonteCarloViews(), &flicker);
    for (const ViewResiduals& r : c->after.views) {
      if (!MonteCarloViews().test(static_cast<int>(r.view))) full.views.push_back(r);
    }
    std::stable_sort(full.views.begin(), full.views.end(), [](const ViewResiduals& a, const ViewResiduals& b) {
      return static_cast<int>(a.view) < static_cast<int>(b.view);
    });
  } else {
    full = Assess(ctx, c->model, true, ctx.options->seed + salt, &note, c->theory.mean.empty() ? nullptr : &c->theory);
  }
  full.heldout = c->after.heldout;
  full.has_heldout = c->after.has_heldout;
  c->after = std::move(full);
  HeldoutViews(ctx, s.threshold, c, ctx.options->seed + 100000 + salt);
  c->full_views = true;
  c->full_score = s.before.All().chi2 - c->after.All().chi2 - 2.0 * ParameterCount(c->effects);
}

// Records up to this many samples have candidates whose views come from theory assessed side by
// side (AssessChosen, GrowSet). Their serial steps then overlap: ADIS16405 imu1 Gyro_Z (1e6
// samples) 14.4 -> 12.0 s (one run each). On longer records the exact sums dominate and already
// use every thread, and two candidates' record-sized arrays at once contend for the memory: a
// 1e7-sample record with a Gauss-Markov gap took 46.8-47.7 s side by side against 43.6-43.9 s one
// after another (two runs each, interleaved).
constexpr std::int64_t kSideBySideMaxSamples = std::int64_t{1} << 22;

// Whether FullAssess finds the candidate's Monte Carlo views from theory (gaussian_views.h) rather
// than from simulated records, on a record short enough for them to be assessed side by side.
bool SideBySide(const Context& ctx, const CandidateResult& c) {
  if (ctx.layout.num_samples > kSideBySideMaxSamples) return false;
  sim::SensorModel gaussian_part;
  return IsGaussianModel(c.model, ctx.layout.num_samples) ||
         SplitWarmupDrift(c.model, ctx.layout.num_samples, &gaussian_part).has_value();
}

// FullAssess of the chosen candidates (each seeded by its index, so the order of the calls does
// not matter); closes_gap and the score of every candidate not deferred from its assessed views.
void AssessChosen(const Context& ctx, DiagnosisSummary* s, const std::vector<std::size_t>& chosen) {
  // A model with its Monte Carlo views from theory (gaussian_views.h) is assessed mostly in serial
  // steps (autocovariance, variogram, block means): on records up to kSideBySideMaxSamples those
  // candidates run in parallel, each on its own thread, where one after another they left the
  // second core idle for most of this stage. A model whose views are simulated spends its time in
  // envelopes that use every thread: those run first, one at a time, as do all on longer records.
  // Each candidate writes only itself and reads what is shared and fixed (the held-out halves'
  // baselines are computed once, by whichever thread first needs them), so the bits are those of
  // any other order.
  std::vector<std::size_t> one_at_a_time, side_by_side;
  for (std::size_t i : chosen) (SideBySide(ctx, s->candidates[i]) ? side_by_side : one_at_a_time).push_back(i);
  const int count = static_cast<int>(chosen.size());
  std::atomic<int> done{0};
  if (count > 0) ReportProgress(ctx, "Monte Carlo views", 0, count);
  auto report = [&] {
    const int d = done.fetch_add(1) + 1;
    if (d < count) ReportProgress(ctx, "Monte Carlo views", d, count);
  };
  for (std::size_t i : one_at_a_time) {
    FullAssess(ctx, *s, &s->candidates[i], 1000 + i);
    report();
  }
  const int parallel = static_cast<int>(side_by_side.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (int j = 0; j < parallel; ++j) {
    const std::size_t i = side_by_side[static_cast<std::size_t>(j)];
    FullAssess(ctx, *s, &s->candidates[i], 1000 + i);
    report();
  }
  if (count > 0) ReportProgress(ctx, "Monte Carlo views", count, count);
  for (CandidateResult& c : s->candidates) {
    if (!c.full_views) c.full_score = c.score;
    c.closes_gap = ClosesGap(c.after, s->threshold);
  }
}

// Every candidate that leaves the OAVAR view no worse than its penalty (+2 for noise) gets the
// Monte Carlo views, and the best `envelope_candidates` in any case: the signatures of spikes
// (kurtosis), steps and warm-up drifts (halves, dynamic) and quantizers (kurtosis, PSD) lie
// outside the Allan view, so its score alone cannot rank them. Allan-equivalent pairs
// (telegraph / Gauss-Markov) share their score and so are assessed together. When the record
// departs in Monte Carlo views only, the exact score is noise for every candidate: then each
// candidate whose effect shows in a departing view is assessed too, whatever its score (a
// dithered quantizer seen only in the kurtosis scored -4.9 on OAVAR, was never assessed, and the
// record was left unexplained).
// Those that already leave a point of their exact views beyond the threshold can never be
// acceptable (closes_gap needs every view), so with a record their envelopes wait: they are
// simulated only when no candidate turns out acceptable without them (a partial verdict or a set
// needs them), with the seeds they would have had, so that case gives the same bits as
// simulating them all at once. On a record with a gap they were most of the Monte Carlo views' CPU.
void AssessMonteCarlo(const Context& ctx, DiagnosisSummary* s) {
  ViewSet departing_monte_carlo;
  bool departs_in_exact_view = false;
  for (const ViewResiduals& r : s->before.views) {
    if (!(Metrics(r.z).max_abs_z > s->threshold)) continue;
    if (MonteCarloViews().test(static_cast<int>(r.view))) {
      departing_monte_carlo.set(static_cast<int>(r.view));
    } else {
      departs_in_exact_view = true;
    }
  }
  if (departs_in_exact_view) departing_monte_carlo.reset();
  auto shows_where_departing = [&](const CandidateResult& c) {
    for (const EffectInstance& e : c.effects) {
      for (View v : SpecOf(e.effect).views) {
        if (departing_monte_carlo.test(static_cast<int>(v))) return true;
      }
    }
    return false;
  };
  std::vector<std::size_t> chosen;
  const bool can_defer = ctx.options->defer_envelopes && ctx.have_record && ctx.options->trials >= 3;
  for (std::size_t i = 0; i < s->candidates.size(); ++i) {
    CandidateResult& c = s->candidates[i];
    const int k = ParameterCount(c.effects);
    if (c.score < -2.0 * k - 2.0 && static_cast<int>(i) >= ctx.options->envelope_candidates &&
        !shows_where_departing(c)) {
      continue;
    }
    if (can_defer && !ClosesGap(c.after, s->threshold)) {
      c.monte_carlo_deferred = true;
      continue;
    }
    chosen.push_back(i);
  }
  AssessChosen(ctx, s, chosen);
}

// The deferred candidates' Monte Carlo views (AssessMonteCarlo), once no candidate is acceptable
// without them.
void AssessDeferred(const Context& ctx, DiagnosisSummary* s) {
  std::vector<std::size_t> chosen;
  for (std::size_t i = 0; i < s->candidates.size(); ++i) {
    if (s->candidates[i].monte_carlo_deferred) chosen.push_back(i);
  }
  for (std::size_t i : chosen) s->candidates[i].monte_carlo_deferred = false;
  AssessChosen(ctx, s, chosen);
}

// A candidate that may be the verdict: a positive penalised score, every view within the
// threshold, and a held-out score no worse than the AIC penalty (an effect outside the Allan view
// cannot improve it).
bool Acceptable(const Context& ctx, const CandidateResult& c) {
  const bool heldout_ok = !c.after.has_heldout ||
                          c.after.heldout.chi2 < c.heldout_before.chi2 + 2.0 * ParameterCount(c.effects);
  const int trials = ctx.options->trials;
  return (c.full_views ? c.full_score : c.score) > 0.0 && c.closes_gap && heldout_ok &&
         (c.full_views || !ctx.have_record || trials < 3);
}

double HeldoutShrink(const CandidateResult& c) {
  return c.after.has_heldout && c.after.heldout.chi2 > 0.0 ? c.heldout_before.chi2 / c.after.heldout.chi2 : 0.0;
}

// A view where the baseline departs must keep at most this share of its chi2 under a partial
// verdict.
constexpr double kPartialViewShrink = 2.0;

// When no candidate closes the gap: the one that explains most of it, if it explains enough to be
// named. Every view assessed, a positive penalised score, the held-out chi2 down by at least
// ctx.options->partial_shrink, and the record's chi2 summed over the views where the baseline
// departs (a point beyond the threshold) down by that factor too, each of them at least halved;
// of those, the best penalised score. -1 when none. Per view, the factor itself asked too much: a
// random telegraph that took the gap's chi2 from 29356 to 77 (held-out 143x) stayed unexplained
// because its dynamic view went from 34 to 8 (4.2x; independent benchmark #94), as did an angle
// quantizer whose kurtosis went 20 -> 5.3 while OAVAR went 5146 -> 89 (#225).
int PickPartial(const Context& ctx, const DiagnosisSummary& s) {
  int best = -1;
  for (std::size_t i = 0; i < s.candidates.size(); ++i) {
    const CandidateResult& c = s.candidates[i];
    if (!c.full_views || c.full_score <= 0.0 || HeldoutShrink(c) < ctx.options->partial_shrink) continue;
    bool every_view = true;
    double before_sum = 0.0, after_sum = 0.0;
    for (const ViewResiduals& r : s.before.views) {
      const GapMetrics before = Metrics(r.z), after = c.after.View(r.view);
      if (!(before.max_abs_z > s.threshold && after.points > 0)) continue;
      every_view &= after.chi2 * kPartialViewShrink <= before.chi2;
      before_sum += before.chi2;
      after_sum += after.chi2;
    }
    if (!every_view || !(after_sum * ctx.options->partial_shrink <= before_sum)) continue;
    if (best < 0 || c.full_score > s.candidates[best].full_score) best = static_cast<int>(i);
  }
  return best;
}

// Penalised scores closer than this the record cannot tell apart: 2, AIC's scale, or on a large
// gap one standard deviation of a chi-square over the points the scores sum, sqrt(2 n). Two
// candidates that both close a large gap are both misspecified to some degree, and their chi2
// over the same points then differ by that much with the noise alone (the independent
// benchmark's angle quantizer of seed 4, #160, 14 levels in its samples: score 1572 against a
// band-limit's 1584 over 135 points, while its held-out shrink was 6.9x against 3.3x).
double ScoreTie(const DiagnosisSummary& s) {
  return std::max(2.0, std::sqrt(2.0 * static_cast<double>(s.before.All().points)));
}

// The acceptable candidate with the best penalised score; of those within ScoreTie of it (which
// the record cannot tell apart: a telegraph whose dwell outlasts the record is one step), the data
// the fit did not see decide, the largest held-out shrink. -1 when none is acceptable.
int Pick(const Context& ctx, const DiagnosisSummary& s) {
  int best = -1;
  for (std::size_t i = 0; i < s.candidates.size(); ++i) {
    if (!Acceptable(ctx, s.candidates[i])) continue;
    if (best < 0 || s.candidates[i].full_score > s.candidates[best].full_score) best = static_cast<int>(i);
  }
  if (best < 0) return best;
  int chosen = best;
  for (std::size_t i = 0; i < s.candidates.size(); ++i) {
    const CandidateResult& c = s.candidates[i];
    if (!Acceptable(ctx, c) || c.full_score < s.candidates[best].full_score - ScoreTie(s)) continue;
    if (HeldoutShrink(c) > HeldoutShrink(s.candidates[chosen])) chosen = static_cast<int>(i);
  }
  return chosen;
}

// The held-out score of `current` on the half and views `next` is scored on, so that the two
// compare (the same numbers when both are scored alike; else current's model for that half,
// scored there the same way), and its per-view residuals where it has them (*residuals).
GapMetrics HeldoutOnSameFooting(const Context& ctx, double threshold, const CandidateResult& current,
                                const CandidateResult& next, std::uint64_t seed,
                                std::vector<ViewResiduals>* residuals) {
  residuals->clear();
  if (current.heldout_half == next.heldout_half && current.heldout_in_gap_views == next.heldout_in_gap_views) {
    *residuals = current.heldout_residuals;
    return current.after.heldout;
  }
  sim::SensorModel model = current.heldout_model;
  std::string ignored;
  if (current.heldout_half != next.heldout_half &&
      !HeldoutModel(ctx, current.effects, next.heldout_half, &model, &ignored)) {
    return current.heldout_before;
  }
  return HeldoutScore(ctx, threshold, model, next.heldout_half, next.heldout_in_gap_views, seed, residuals);
}

// Forward selection when no single effect closes the gap: from the single with the largest
// held-out shrink (positive score, all views assessed), each round joins every pool effect
// (SetPool, not already a member nor Allan-equivalent to one) to the set, refits, and takes, of
// the kTriesPerRound joins that shrink the held-out chi2 most, the first (in that order) that earns
// its place (EarnsItsPlace); it stops when none does, the set closes the gap or has max_effects
// members. Every set kept is appended to the candidates with its steps (what each member added,
// held-out chi2 before -> after).
void GrowSet(const Context& ctx, DiagnosisSummary* s) {
  constexpr std::size_t kTriesPerRound = 3;
  const int max_effects = ctx.options->max_effects;
  int seed = -1;
  for (std::size_t i = 0; i < s->candidates.size(); ++i) {
    const CandidateResult& c = s->candidates[i];
    if (c.effects.size() != 1 || !c.full_views || !c.after.has_heldout || c.full_score <= 0.0) continue;
    if (seed < 0 || HeldoutShrink(c) > HeldoutShrink(s->candidates[seed])) seed = static_cast<int>(i);
  }
  if (seed < 0 || max_effects < 2) return;
  const std::vector<std::size_t> pool = SetPool(*s);
  CandidateResult current = s->candidates[seed];
  current.steps = {{current.effects[0].effect, current.heldout_before, current.after.heldout, {}, {}}};
  s->candidates[seed].steps = current.steps;
  for (std::uint64_t round = 0; static_cast<int>(current.effects.size()) < max_effects && !current.closes_gap; ++round) {
    std::vector<std::vector<EffectInstance>> sets;
    for (std::size_t i : pool) {
      const EffectInstance& e = s->candidates[i].effects[0];
      if (Clashes(current.effects, e.effect)) continue;
      sets.push_back(current.effects);
      sets.back().push_back(e);
    }
    // Independent refits, in parallel; kept in pool order, so the outcome is the same for any
    // thread count.
    std::vector<std::optional<CandidateResult>> tried(sets.size());
    const std::string stage = "sets of " + std::to_string(current.effects.size() + 1);
    const int set_count = static_cast<int>(sets.size());
    std::atomic<int> done{0};
    ReportProgress(ctx, stage, 0, set_count);
#pragma omp parallel for schedule(dynamic, 1)
    for (std::size_t i = 0; i < sets.size(); ++i) {
      std::string why;
      tried[i] = TryCandidate(ctx, *s, sets[i], &why);
      ReportProgress(ctx, stage, done.fetch_add(1) + 1, set_count);
    }
    std::vector<CandidateResult> trials;
    for (auto& c : tried) {
      if (c) trials.push_back(std::move(*c));
    }
    std::stable_sort(trials.begin(), trials.end(), [](const CandidateResult& a, const CandidateResult& b) {
      return HeldoutShrink(a) > HeldoutShrink(b);
    });
    if (trials.size() > kTriesPerRound) trials.resize(kTriesPerRound);
    // Each try's Monte Carlo views and held-out footing depend on it and the current set alone
    // (seeded by its place): those that SideBySide allows are assessed in parallel beforehand
    // when there are two or more, though a try kept first makes the later ones unneeded; the
    // others (simulated views, whose envelopes use every thread) when the loop reaches them.
    struct Assessed {
      bool done = false;
      GapMetrics before;
      std::vector<ViewResiduals> before_residuals;
    };
    std::vector<Assessed> assessed(trials.size());
    auto assess = [&](std::size_t t) {
      FullAssess(ctx, *s, &trials[t], 2000 + 10 * round + t);
      trials[t].closes_gap = ClosesGap(trials[t].after, s->threshold);
      assessed[t].before = HeldoutOnSameFooting(ctx, s->threshold, current, trials[t],
                                                ctx.options->seed + 3000 + 10 * round + t,
                                                &assessed[t].before_residuals);
      assessed[t].done = true;
    };
    std::vector<std::size_t> side_by_side;
    for (std::size_t t = 0; t < trials.size(); ++t) {
      if (SideBySide(ctx, trials[t])) side_by_side.push_back(t);
    }
    if (side_by_side.size() > 1) {
      ReportProgress(ctx, stage + ": Monte Carlo views", 0, static_cast<int>(trials.size()));
      const int count = static_cast<int>(side_by_side.size());
#pragma omp parallel for schedule(dynamic, 1)
      for (int j = 0; j < count; ++j) assess(side_by_side[static_cast<std::size_t>(j)]);
    }
    bool kept = false;
    for (std::size_t t = 0; t < trials.size() && !kept; ++t) {
      CandidateResult& next = trials[t];
      if (!assessed[t].done) {
        ReportProgress(ctx, stage + ": Monte Carlo views", static_cast<int>(t), static_cast<int>(trials.size()));
        assess(t);
      }
      const GapMetrics& before = assessed[t].before;
      const std::vector<ViewResiduals>& before_residuals = assessed[t].before_residuals;
      std::string why;
      CandidateResult::Step step;
      if (!EarnsItsPlace(ctx.options->set_margin, s->threshold, s->before, current, next, before, before_residuals,
                         &step, &why)) {
        s->notes.push_back("set: " + next.id() + " not kept over " + current.id() + " (" + why + ")");
        continue;
      }
      next.steps = current.steps;
      next.steps.push_back(step);
      current = next;
      s->candidates.push_back(next);
      kept = true;
    }
    if (!kept) return;
  }
}

// Allan-equivalent effects (telegraph vs Gauss-Markov) have the same number of parameters and the
// same Allan score: the view that separates them decides (lower chi2 there).
int ResolveEquivalents(const Context& ctx, const DiagnosisSummary& s, int best) {
  if (s.candidates[best].effects.size() != 1) return best;
  const Effect e = s.candidates[best].effects[0].effect;
  for (const auto& eq : AllanEquivalents(e)) {
    const View* view_it = std::find_if(std::begin(kAllViews), std::end(kAllViews),
                                       [&](View v) { return ViewId(v) == eq.separating_view; });
    if (view_it == std::end(kAllViews)) continue;
    const View view = *view_it;
    for (std::size_t i = 0; i < s.candidates.size(); ++i) {
      const CandidateResult& c = s.candidates[i];
      if (c.effects.size() != 1 || c.effects[0].effect != eq.other || !Acceptable(ctx, c)) continue;
      const GapMetrics mine = s.candidates[best].after.View(view), theirs = c.after.View(view);
      if (theirs.points > 0 && mine.points > 0 && theirs.chi2 < mine.chi2) best = static_cast<int>(i);
      break;
    }
  }
  return best;
}

// A harmonic and a resonance that both close the gap near one frequency: the views cannot tell a
// sinusoid from a narrow line, the whole record's periodogram can (line_shape.h). Searched over
// three of the resonance's line widths.
int ResolveLineShape(const Context& ctx, DiagnosisSummary* s, int best) {
  const CandidateResult& chosen = s->candidates[best];
  if (!ctx.have_record || chosen.effects.size() != 1) return best;
  const Effect e = chosen.effects[0].effect;
  if (e != Effect::kHarmonic && e != Effect::kResonance) return best;
  const Effect other = e == Effect::kHarmonic ? Effect::kResonance : Effect::kHarmonic;
  for (std::size_t i = 0; i < s->candidates.size(); ++i) {
    const CandidateResult& c = s->candidates[i];
    if (c.effects.size() != 1 || c.effects[0].effect != other || !Acceptable(ctx, c)) continue;
    const EffectInstance& harmonic = e == Effect::kHarmonic ? chosen.effects[0] : c.effects[0];
    const EffectInstance& resonance = e == Effect::kResonance ? chosen.effects[0] : c.effects[0];
    const double f = harmonic.params.at("frequency_hz"), f0 = resonance.params.at("frequency_hz");
    const double width_hz = 2.0 * resonance.params.at("damping") * f0;
    if (std::abs(f - f0) > std::max(3.0 * width_hz, 0.01 * f0)) return best;  // two different lines
    s->line_lobe_share = LineLobeShare(ctx.rate, ctx.curve.sample_clock.period_s(), f, 3.0 * width_hz);
    const bool sinusoid = s->line_lobe_share >= kSinusoidLobeShare;
    s->notes.push_back("harmonic or resonance: the line at " + SignificantDigits(f, 4) + " Hz holds " +
                       SignificantDigits(100.0 * s->line_lobe_share, 3) +
                       " % of its power within the main lobe of the whole record's periodogram: " + (sinusoid ? "a sinusoid" : "a line wider than a sinusoid's"));
    const bool keep = sinusoid == (e == Effect::kHarmonic);
    return keep ? best : static_cast<int>(i);
  }
  return best;
}

// A record whose samples sit on a value grid is quantized, whatever else it shows: when a
// quantizer of that step closes the gap by itself, it names the record over another single effect
// that closes it too, whatever their scores (an independent angle quantizer whose 242093 samples
// took 16 values had been named a band-limit that scored 19 higher over 130 points).
int ResolveValueGrid(const Context& ctx, DiagnosisSummary* s, int best) {
  const CandidateResult& chosen = s->candidates[best];
  if (!ctx.have_record || chosen.effects.size() != 1) return best;
  const auto is_quantizer = [](Effect e) { return e == Effect::kAngleQuantization || e == Effect::kRateQuantization; };
  if (is_quantizer(chosen.effects[0].effect)) return best;
  const std::optional<double> grid = RecordValueGrid(ctx.rate);
  if (!grid) return best;
  const double tau0 = ctx.curve.sample_clock.period_s();
  for (std::size_t i = 0; i < s->candidates.size(); ++i) {
    const CandidateResult& c = s->candidates[i];
    if (c.effects.size() != 1 || !is_quantizer(c.effects[0].effect) || !Acceptable(ctx, c)) continue;
    const EffectInstance& q = c.effects[0];
    const double step = q.effect == Effect::kAngleQuantization ? q.params.at("lsb_rad") / tau0 : q.params.at("lsb_rad_per_s");
    if (!(std::abs(step - *grid) <= 1e-6 * *grid)) continue;
    s->value_grid_rad_per_s = *grid;
    // The grid's step is reported in the record's own terms by the caller (a gyro's deg/h, an
    // accelerometer's mg): value_grid_rad_per_s.
    s->notes.push_back("quantized: the samples sit on a value grid, which " + c.id() + " makes and " + chosen.id() +
                       " does not; both close the gap");
    return static_cast<int>(i);
  }
  return best;
}

// Also consistent with the verdict: effects with the same Allan signature (unless a view has told
// them apart) and any other acceptable candidate whose penalised score is within ScoreTie of it.
void ListAlsoConsistent(const Context& ctx, DiagnosisSummary* s) {
  const int best = s->verdict_candidate;
  const CandidateResult& chosen = s->candidates[best];
  if (chosen.effects.size() == 1) {
    for (const auto& eq : AllanEquivalents(chosen.effects[0].effect)) {
      bool separated = false;
      for (const CandidateResult& c : s->candidates) {
        // A deferred one already leaves its exact views: separated as if its envelopes had been simulated.
        if (c.effects.size() == 1 && c.effects[0].effect == eq.other && (c.full_views || c.monte_carlo_deferred) &&
            !c.closes_gap) {
          separated = true;
        }
      }
      if (!separated) s->also_consistent.push_back({std::string(EffectId(eq.other)), eq.separating_view});
    }
  }
  // A first-order low-pass of white noise is a Gauss-Markov process with Tc = 1/(2 pi fc): a
  // Gauss-Markov verdict whose refit leaves no white rate noise (N dropped or within 2 sigma of
  // zero) is equally a band-limit, and no view of second moments or kurtosis (both Gaussian)
  // separates them.
  if (chosen.effects.size() == 1 && chosen.effects[0].effect == Effect::kGaussMarkov) {
    const auto& n = chosen.fit.at(Coefficient::kN);
    if (!n.fitted || n.value_si <= 2.0 * n.sigma_si) s->also_consistent.push_back({"bandwidth", ""});
  }
  for (std::size_t i = 0; i < s->candidates.size(); ++i) {
    const CandidateResult& c = s->candidates[i];
    if (static_cast<int>(i) == best || !Acceptable(ctx, c)) continue;
    if (chosen.full_score - c.full_score > ScoreTie(*s)) continue;
    const std::string id = c.id();
    const bool listed = std::any_of(s->also_consistent.begin(), s->also_consistent.end(),
                                    [&](const AlsoConsistent& a) { return a.effect == id; });
    if (!listed) s->also_consistent.push_back({id, ""});
  }
}

std::string Num(double v) { return SignificantDigits(v, 4); }

// The assessed view with the largest |z| of `gap`, as "kurtosis |z| 4.888".
std::string WorstView(const ModelGap& gap) {
  const ViewResiduals* worst = nullptr;
  double worst_z = -1.0;
  for (const ViewResiduals& r : gap.views) {
    const double z = Metrics(r.z).max_abs_z;
    if (z > worst_z) worst = &r, worst_z = z;
  }
  return worst == nullptr ? "" : std::string(ViewId(worst->view)) + " |z| " + Num(worst_z);
}

// Why `c` is not the verdict: the first rule of Acceptable (and Pick, ResolveEquivalents) it
// fails, with its numbers, in the order a reader checks them.
std::string WhyNotVerdict(const Context& ctx, const DiagnosisSummary& s, const CandidateResult& c) {
  const int k = ParameterCount(c.effects);
  const std::string scored = c.full_views ? "on every view" : "on the Allan variance (oavar) only";
  if (c.monte_carlo_deferred) {
    return "does not close the gap on its exact views: " + WorstView(c.after) + " beyond " + Num(s.threshold) +
           " (its Monte Carlo views were not simulated: an acceptable candidate needed none of them)";
  }
  if (!c.full_views && ctx.have_record && ctx.options->trials >= 3) {
    return "scored on the Allan variance (oavar) only: its score there (" + Num(c.score) +
           ") ranked too low for the other views to be simulated" +
           (c.closes_gap ? "" : "; it leaves " + WorstView(c.after) + " beyond " + Num(s.threshold));
  }
  if (!c.closes_gap) {
    return "does not close the gap (scored " + scored + "): " + WorstView(c.after) + " beyond " + Num(s.threshold);
  }
  const double score = c.full_views ? c.full_score : c.score;
  if (score <= 0.0) {
    return "closes the gap, but its chi2 gain does not pay for its " + std::to_string(k) +
           " parameter(s): penalised score " + Num(score) + " (scored " + scored + ")";
  }
  if (c.after.has_heldout && !(c.after.heldout.chi2 < c.heldout_before.chi2 + 2.0 * k)) {
    return "closes the gap, but fitted on one half it does not improve the other: held-out chi2 " +
           Num(c.heldout_before.chi2) + " -> " + Num(c.after.heldout.chi2);
  }
  if (s.verdict_candidate < 0 || !s.explains_all || s.verdict == "unexplained") return "";
  const CandidateResult& v = s.candidates[s.verdict_candidate];
  if (c.effects.size() == 1 && v.effects.size() == 1) {
    for (const auto& eq : AllanEquivalents(v.effects[0].effect)) {
      if (eq.other != c.effects[0].effect || eq.separating_view.empty()) continue;
      const std::string view = eq.separating_view;
      for (View w : kAllViews) {
        if (ViewId(w) != view) continue;
        const GapMetrics mine = c.after.View(w), theirs = v.after.View(w);
        if (mine.points > 0 && theirs.points > 0 && theirs.chi2 < mine.chi2) {
          return "closes the gap too, with the same Allan variance as " + v.id() + "; the " + view +
                 " view tells them apart: chi2 " + Num(mine.chi2) + " against " + Num(theirs.chi2);
        }
      }
    }
  }
  if (c.effects.size() == 1 && v.effects.size() == 1 && std::isfinite(s.line_lobe_share) &&
      (c.effects[0].effect == Effect::kHarmonic || c.effects[0].effect == Effect::kResonance)) {
    // The share itself is in the notes (ResolveLineShape): said once.
    return "closes the gap too; the line's shape in the whole record's periodogram names " + v.id() +
           " (see the notes)";
  }
  if (c.effects.size() == 1 && std::isfinite(s.value_grid_rad_per_s)) {
    return "closes the gap too; the samples sit on the value grid " + v.id() + " makes (see the notes)";
  }
  if (v.full_score - score > ScoreTie(s)) {
    return "closes the gap too, with a penalised score " + Num(v.full_score - score) + " below " + v.id() + "'s (" +
           Num(score) + " against " + Num(v.full_score) + ")";
  }
  const double d = score - v.full_score;
  return "closes the gap too, with a penalised score within " + Num(ScoreTie(s)) + " of " + v.id() + "'s (" + Num(std::abs(d)) +
         (d > 0.0 ? " above" : " below") + "), which the record cannot tell apart; " + v.id() +
         " shrinks the held-out chi2 more (" + Num(HeldoutShrink(v)) + "x against " + Num(HeldoutShrink(c)) + "x)";
}

// The line a resonance or harmonic candidate was fitted to, measured along the record
// (line_drift.h): the verdict's (or best tried) model's line when it has one, else the line of the
// best scoring candidate that has one.
void MeasureCandidateLine(const Context& ctx, DiagnosisSummary* s) {
  if (!ctx.have_record) return;
  auto line_of = [](const CandidateResult& c) -> const EffectInstance* {
    for (const EffectInstance& e : c.effects) {
      if (e.effect == Effect::kResonance || e.effect == Effect::kHarmonic) return &e;
    }
    return nullptr;
  };
  const EffectInstance* line = s->verdict_candidate >= 0 ? line_of(s->candidates[s->verdict_candidate]) : nullptr;
  if (line == nullptr) {
    double best_score = -std::numeric_limits<double>::infinity();
    for (const CandidateResult& c : s->candidates) {
      const EffectInstance* e = line_of(c);
      if (e != nullptr && c.full_score > best_score) {
        best_score = c.full_score;
        line = e;
      }
    }
  }
  if (line == nullptr) return;
  const double f0 = line->params.at("frequency_hz");
  const double halfwidth_hz = line->effect == Effect::kResonance ? line->params.at("damping") * f0 : 0.0;
  s->line_drift = MeasureLineDrift(ctx.rate, ctx.curve.sample_clock.period_s(), f0, halfwidth_hz);
  if (s->line_drift) s->line_drift_frequency_hz = f0;
}

}  // namespace

void Finish(const Context& ctx, DiagnosisSummary* s) {
  const DiagnoseOptions& o = *ctx.options;
  s->total_points = s->before.All().points;
  s->threshold = BonferroniThreshold(o.false_alarm, s->total_points);
  s->regions = FindGapRegions(s->before.views, s->threshold);
  s->significant = !s->regions.empty();
  s->verdict = "none";
  if (!s->significant) return;

  RankSingles(ctx, s);
  AssessMonteCarlo(ctx, s);
  int best = Pick(ctx, *s);
  if (best < 0 && std::any_of(s->candidates.begin(), s->candidates.end(),
                              [](const CandidateResult& c) { return c.monte_carlo_deferred; })) {
    AssessDeferred(ctx, s);
    best = Pick(ctx, *s);  // the same: a deferred candidate is never acceptable
  }
  if (best < 0 && o.max_effects > 1) {
    GrowSet(ctx, s);
    best = Pick(ctx, *s);
  }
  if (best < 0) {
    best = PickPartial(ctx, *s);
    s->explains_all = false;
  }
  if (best < 0) {
    s->verdict = "unexplained";
    for (std::size_t i = 0; i < s->candidates.size(); ++i) {
      if (s->verdict_candidate < 0 ||
          s->candidates[i].full_score > s->candidates[s->verdict_candidate].full_score) {
        s->verdict_candidate = static_cast<int>(i);
      }
    }
  } else {
    s->verdict_candidate = ResolveValueGrid(ctx, s, ResolveLineShape(ctx, s, ResolveEquivalents(ctx, *s, best)));
    s->verdict = s->candidates[s->verdict_candidate].id();
    ListAlsoConsistent(ctx, s);
  }
  if (s->verdict_candidate >= 0) {
    CandidateResult& c = s->candidates[s->verdict_candidate];
    if (c.steps.empty() && c.effects.size() == 1 && c.after.has_heldout) {
      c.steps = {{c.effects[0].effect, c.heldout_before, c.after.heldout, {}, {}}};
    }
    s->remaining = FindGapRegions(c.after.views, s->threshold);
  }
  MeasureCandidateLine(ctx, s);
  for (std::size_t i = 0; i < s->candidates.size(); ++i) {
    if (static_cast<int>(i) == s->verdict_candidate && s->verdict != "unexplained") continue;
    s->candidates[i].why_not_verdict = WhyNotVerdict(ctx, *s, s->candidates[i]);
  }
}

}  // namespace allanlab::experiments::detail
