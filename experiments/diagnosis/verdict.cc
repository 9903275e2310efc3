#include "experiments/diagnosis/verdict.h"

#include <algorithm>
#include <atomic>
#include <optional>

#include "estimators/fit/noise_coefficient.h"
#include "experiments/diagnosis/block_means.h"
#include "experiments/diagnosis/candidate_estimate.h"
#include "experiments/diagnosis/heldout.h"

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
  ModelGap full = Assess(ctx, c->model, true, ctx.options->seed + salt, &note);
  full.heldout = c->after.heldout;
  full.has_heldout = c->after.has_heldout;
  c->after = std::move(full);
  HeldoutViews(ctx, s.threshold, c, ctx.options->seed + 100000 + salt);
  c->full_views = true;
  c->full_score = s.before.All().chi2 - c->after.All().chi2 - 2.0 * ParameterCount(c->effects);
}

// Every candidate that leaves the OAVAR view no worse than its penalty (+2 for noise) gets the
// Monte Carlo views, and the best `envelope_candidates` in any case: the signatures of spikes
// (kurtosis), steps and warm-up drifts (halves, dynamic) and quantizers (kurtosis, PSD) lie
// outside the Allan view, so its score alone cannot rank them. Allan-equivalent pairs
// (telegraph / Gauss-Markov) share their score and so are assessed together.
void AssessMonteCarlo(const Context& ctx, DiagnosisSummary* s) {
  std::vector<std::size_t> chosen;
  for (std::size_t i = 0; i < s->candidates.size(); ++i) {
    const CandidateResult& c = s->candidates[i];
    const int k = ParameterCount(c.effects);
    if (c.score < -2.0 * k - 2.0 && static_cast<int>(i) >= ctx.options->envelope_candidates) continue;
    chosen.push_back(i);
  }
  for (std::size_t j = 0; j < chosen.size(); ++j) {
    ReportProgress(ctx, "Monte Carlo views", static_cast<int>(j), static_cast<int>(chosen.size()));
    FullAssess(ctx, *s, &s->candidates[chosen[j]], 1000 + chosen[j]);
  }
  for (CandidateResult& c : s->candidates) {
    if (!c.full_views) c.full_score = c.score;
    c.closes_gap = ClosesGap(c.after, s->threshold);
  }
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

// The acceptable candidate with the best penalised score; of those within 2 of it (which the
// record cannot tell apart: a telegraph whose dwell outlasts the record is one step), the data the
// fit did not see decide, the largest held-out shrink. -1 when none is acceptable.
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
    if (!Acceptable(ctx, c) || c.full_score < s.candidates[best].full_score - 2.0) continue;
    if (HeldoutShrink(c) > HeldoutShrink(s.candidates[chosen])) chosen = static_cast<int>(i);
  }
  return chosen;
}

// Pairs of the best three single effects with a positive score (Allan-equivalent pairs skipped),
// appended to the candidates; the best pair gets the Monte Carlo views.
void TryPairs(const Context& ctx, DiagnosisSummary* s) {
  std::vector<std::size_t> top;
  for (std::size_t i = 0; i < s->candidates.size() && top.size() < 3; ++i) {
    if (s->candidates[i].effects.size() == 1 && s->candidates[i].score > 0.0) top.push_back(i);
  }
  std::vector<std::vector<EffectInstance>> sets;
  for (std::size_t a = 0; a < top.size(); ++a) {
    for (std::size_t b = a + 1; b < top.size(); ++b) {
      const auto& ea = s->candidates[top[a]].effects[0];
      const auto& eb = s->candidates[top[b]].effects[0];
      bool equivalent = false;
      for (const auto& eq : AllanEquivalents(ea.effect)) equivalent |= eq.other == eb.effect;
      if (!equivalent) sets.push_back({ea, eb});
    }
  }
  // Independent refits, in parallel; kept in the order above.
  std::vector<std::optional<CandidateResult>> tried(sets.size());
  ReportProgress(ctx, "pairs", 0, static_cast<int>(sets.size()));
#pragma omp parallel for schedule(dynamic, 1)
  for (std::size_t i = 0; i < sets.size(); ++i) {
    std::string why;
    tried[i] = TryCandidate(ctx, *s, sets[i], &why);
  }
  std::vector<CandidateResult> pairs;
  for (auto& c : tried) {
    if (c) pairs.push_back(std::move(*c));
  }
  std::stable_sort(pairs.begin(), pairs.end(), ByScore);
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    if (i == 0 && pairs[i].score > 0.0) FullAssess(ctx, *s, &pairs[i], 2000);
    if (!pairs[i].full_views) pairs[i].full_score = pairs[i].score;
    pairs[i].closes_gap = ClosesGap(pairs[i].after, s->threshold);
    s->candidates.push_back(std::move(pairs[i]));
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

// Also consistent with the verdict: effects with the same Allan signature (unless a view has told
// them apart) and any other acceptable candidate whose penalised score is within 2 of it.
void ListAlsoConsistent(const Context& ctx, DiagnosisSummary* s) {
  const int best = s->verdict_candidate;
  const CandidateResult& chosen = s->candidates[best];
  if (chosen.effects.size() == 1) {
    for (const auto& eq : AllanEquivalents(chosen.effects[0].effect)) {
      bool separated = false;
      for (const CandidateResult& c : s->candidates) {
        if (c.effects.size() == 1 && c.effects[0].effect == eq.other && c.full_views && !c.closes_gap) {
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
    if (chosen.full_score - c.full_score > 2.0) continue;
    const std::string id = c.id();
    const bool listed = std::any_of(s->also_consistent.begin(), s->also_consistent.end(),
                                    [&](const AlsoConsistent& a) { return a.effect == id; });
    if (!listed) s->also_consistent.push_back({id, ""});
  }
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
  if (best < 0 && o.try_pairs) {
    TryPairs(ctx, s);
    best = Pick(ctx, *s);
  }
  if (best < 0) {
    s->verdict = "unexplained";
    for (std::size_t i = 0; i < s->candidates.size(); ++i) {
      if (s->verdict_candidate < 0 ||
          s->candidates[i].full_score > s->candidates[s->verdict_candidate].full_score) {
        s->verdict_candidate = static_cast<int>(i);
      }
    }
    return;
  }
  s->verdict_candidate = ResolveEquivalents(ctx, *s, best);
  s->verdict = s->candidates[s->verdict_candidate].id();
  ListAlsoConsistent(ctx, s);
}

}  // namespace allanlab::experiments::detail
