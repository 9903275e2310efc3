#include "experiments/diagnosis/set_rules.h"

#include <algorithm>

#include "common/number_text.h"
#include "experiments/diagnosis/heldout.h"

namespace allanlab::experiments::detail {
namespace {

// A single's standing for a set: the better of its penalised scores on the exact views and on
// every view (an effect seen outside the exact views, as spikes in the kurtosis, takes part; one
// the Monte Carlo views' noise hides, as a step beside spikes, too).
double PoolScore(const CandidateResult& c) { return std::max(c.score, c.full_score); }

}  // namespace

bool EarnsItsPlace(double margin, double threshold, const ModelGap& baseline, const CandidateResult& current,
                   const CandidateResult& next, const GapMetrics& heldout_before,
                   const std::vector<ViewResiduals>& heldout_before_residuals, CandidateResult::Step* step,
                   std::string* why) {
  const EffectInstance& added = next.effects.back();
  const double penalty = 2.0 * static_cast<double>(EffectParameterNames(added.effect).size());
  const auto& shows = SpecOf(added.effect).views;
  auto falls = [&](const GapMetrics& before, const GapMetrics& after) {
    return after.chi2 <= (1.0 - margin) * before.chi2 - penalty;
  };
  std::vector<View> own_views;
  for (const ViewResiduals& r : next.heldout_residuals) {
    if (std::find(shows.begin(), shows.end(), r.view) != shows.end()) own_views.push_back(r.view);
  }
  const GapMetrics own_before = MetricsOf(heldout_before_residuals, own_views);
  const GapMetrics own_after = MetricsOf(next.heldout_residuals, own_views);
  const bool own_falls = !heldout_before_residuals.empty() && own_before.points > 0 && own_after.points > 0 &&
                         falls(own_before, own_after);
  *step = {added.effect, heldout_before, next.after.heldout, {}, {}};
  if (own_falls && !falls(heldout_before, next.after.heldout)) {
    step->own_views_before = own_before;
    step->own_views_after = own_after;
  }
  if (!next.after.has_heldout || !(falls(heldout_before, next.after.heldout) || own_falls)) {
    *why = "held-out chi2 " + SignificantDigits(heldout_before.chi2, 4) + " -> " + SignificantDigits(next.after.heldout.chi2, 4);
    if (own_before.points > 0 && own_after.points > 0) {
      *why += "; in the views it shows in " + SignificantDigits(own_before.chi2, 4) + " -> " + SignificantDigits(own_after.chi2, 4);
    }
    return false;
  }
  bool explains = false;
  std::string unexplained;
  for (const ViewResiduals& r : next.after.views) {
    const GapMetrics was = current.after.View(r.view), now = Metrics(r.z);
    if (was.points == 0) continue;
    if (was.max_abs_z > threshold && baseline.View(r.view).max_abs_z > threshold &&
        std::find(shows.begin(), shows.end(), r.view) != shows.end()) {
      if (now.chi2 <= (1.0 - margin) * was.chi2) {
        explains = true;
      } else if (unexplained.empty()) {
        unexplained = std::string(ViewId(r.view)) + " chi2 " + SignificantDigits(was.chi2, 4) + " -> " + SignificantDigits(now.chi2, 4);
      }
    }
    if (was.max_abs_z <= threshold && now.max_abs_z > threshold) {
      *why = std::string(ViewId(r.view)) + " leaves the threshold";
      return false;
    }
  }
  if (!explains) *why = unexplained.empty() ? "no view of the effect holds a gap the set leaves" : unexplained;
  return explains;
}

bool Clashes(const std::vector<EffectInstance>& members, Effect e) {
  for (const EffectInstance& member : members) {
    if (member.effect == e) return true;
    for (const auto& eq : AllanEquivalents(member.effect)) {
      if (eq.other == e) return true;
    }
  }
  return false;
}

std::vector<std::size_t> SetPool(const DiagnosisSummary& s) {
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < s.candidates.size(); ++i) {
    const CandidateResult& c = s.candidates[i];
    if (c.effects.size() == 1 && PoolScore(c) > 0.0) order.push_back(i);
  }
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return PoolScore(s.candidates[a]) > PoolScore(s.candidates[b]); });
  std::vector<std::size_t> pool;
  std::vector<EffectInstance> taken;
  std::size_t slots = 0;
  for (std::size_t i : order) {
    const Effect e = s.candidates[i].effects[0].effect;
    const bool pooled = std::any_of(taken.begin(), taken.end(), [e](const EffectInstance& t) { return t.effect == e; });
    const bool joins_its_equivalent = Clashes(taken, e);
    if (pooled || (!joins_its_equivalent && slots == kPoolSize)) continue;
    pool.push_back(i);
    taken.push_back(s.candidates[i].effects[0]);
    if (!joins_its_equivalent) ++slots;
  }
  return pool;
}

}  // namespace allanlab::experiments::detail
