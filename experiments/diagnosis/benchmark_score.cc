#include "experiments/diagnosis/benchmark_score.h"

#include <algorithm>
#include <sstream>

#include <boost/math/distributions/chi_squared.hpp>

#include "experiments/aggregate.h"

namespace allanlab::experiments {
namespace {

// One tau grid step (10 per decade): a region edge one point off is still the same place.
constexpr double kStep = 1.2589254117941673;  // 10^0.1

std::string ParamsText(const std::optional<EffectInstance>& e) {
  if (!e) return "";
  std::ostringstream os;
  os.precision(6);
  bool first = true;
  for (const std::string& name : EffectParameterNames(e->effect)) {
    os << (first ? "" : ";") << name << '=' << e->params.at(name);
    first = false;
  }
  return os.str();
}

}  // namespace

Proportion MakeProportion(int k, int n) {
  Proportion p;
  p.successes = k;
  p.trials = n;
  if (n == 0) return p;
  const RateInterval wilson = WilsonInterval(static_cast<double>(k) / n, n);
  p.low = wilson.low;
  p.high = wilson.high;
  return p;
}

bool NamesEffect(const BenchmarkOutcome& o, const std::string& id) {
  if (!o.ok) return false;
  std::size_t start = 0;
  for (;;) {
    const std::size_t plus = o.verdict.find('+', start);
    if (o.verdict.substr(start, plus == std::string::npos ? std::string::npos : plus - start) == id) return true;
    if (plus == std::string::npos) break;
    start = plus + 1;
  }
  return std::find(o.also_consistent.begin(), o.also_consistent.end(), id) != o.also_consistent.end();
}

std::string VerdictColumn(const BenchmarkOutcome& o) {
  if (!o.ok) return "failed";
  if (o.verdict.find('+') != std::string::npos) return "pair";
  return o.verdict;
}

BenchmarkRow ScoreBenchmarkCase(const BenchmarkCase& c, const BenchmarkOutcome& o) {
  BenchmarkRow r;
  r.index = c.index;
  r.preset = c.preset;
  r.rate_hz = c.sample_clock.rate_hz();
  r.num_samples = c.num_samples;
  r.truth = c.effect ? std::string(EffectId(c.effect->effect)) : "control";
  r.params = c.params_text.empty() ? ParamsText(c.effect) : c.params_text;
  if (c.effect && c.params_text.empty() && !FilterFamilyName(*c.effect).empty()) {
    r.params += ";filter=" + FilterFamilyName(*c.effect);
  }
  r.target_z = c.target_z;
  r.strength_z = c.strength_z;
  r.oavar_z = c.oavar_z;
  r.kurtosis_z = c.kurtosis_z;
  r.halves_z = c.halves_z;
  r.relative_peak = c.relative_peak;
  r.peak_tau_s = c.peak_tau_s;
  r.strength_class = c.strength_class;
  r.outcome = o;
  if (!o.ok) return r;
  // The expected range at the level the diagnosis used: OAVAR taus, else where the view that
  // sees the effect peaks (halves: its peak tau; kurtosis: the sample period).
  auto [lo, hi] = c.ExpectedTauRange(o.threshold_z);
  if (lo == 0.0 && c.halves_z >= o.threshold_z) lo = hi = c.halves_peak_tau_s;
  if (lo == 0.0 && c.kurtosis_z >= o.threshold_z) lo = hi = c.sample_clock.period_s();
  r.expected_tau_min_s = lo;
  r.expected_tau_max_s = hi;
  r.detected = o.significant;
  if (!c.effect) {
    r.right = o.verdict == "none";
    return r;
  }
  r.right = o.verdict == r.truth ||
            std::find(o.also_consistent.begin(), o.also_consistent.end(), r.truth) != o.also_consistent.end();
  if (r.detected && lo > 0.0) {
    r.overlap = r.contain = 0;
    for (const auto& g : o.regions) {
      if (g.tau_min_s <= hi * kStep && g.tau_max_s >= lo / kStep) r.overlap = 1;
      if (g.tau_min_s <= lo * kStep && g.tau_max_s >= hi / kStep) r.contain = 1;
    }
  }
  if (r.right && o.has_heldout && o.heldout_after_chi2 > 0.0) {
    r.shrink = o.heldout_before_chi2 / o.heldout_after_chi2;
    r.heldout_at_model_level =
        o.heldout_points > 0 && o.heldout_after_chi2 <= boost::math::quantile(boost::math::chi_squared(o.heldout_points), 0.95);
  }
  return r;
}

BenchmarkSummary SummarizeBenchmark(const std::vector<BenchmarkRow>& rows) {
  BenchmarkSummary s;
  // Rows for the effects these recordings hold; an effect none of them holds has no rate at all
  // (not a rate of 0/0 among the others) and is listed as not drawn.
  s.truths.push_back("control");
  for (Effect e : kAllEffects) {
    const std::string id(EffectId(e));
    const bool drawn = std::any_of(rows.begin(), rows.end(), [&](const BenchmarkRow& r) { return r.truth == id; });
    (drawn ? s.truths : s.not_drawn).push_back(id);
  }
  s.verdicts.push_back("none");
  for (Effect e : kAllEffects) s.verdicts.emplace_back(EffectId(e));
  for (const char* v : {"pair", "unexplained", "failed"}) s.verdicts.emplace_back(v);
  s.confusion.assign(s.truths.size(), std::vector<int>(s.verdicts.size(), 0));
  auto index_of = [](const std::vector<std::string>& v, const std::string& x) {
    return static_cast<std::size_t>(std::find(v.begin(), v.end(), x) - v.begin());
  };
  int controls = 0, flagged = 0, none = 0, clear = 0, clear_right = 0;
  int overlap_n = 0, overlap_k = 0, contain_k = 0;
  std::vector<double> shrinks;
  int five_or_level = 0;
  const std::vector<double> edges = {0.0, 1.0, 2.0, 5.0, 10.0, 30.0, 1e300};
  std::vector<int> bin_n(edges.size() - 1), bin_det(edges.size() - 1), bin_right(edges.size() - 1);
  std::vector<int> by_n(s.truths.size()), by_k(s.truths.size());
  for (const BenchmarkRow& r : rows) {
    const std::size_t t = index_of(s.truths, r.truth), v = index_of(s.verdicts, VerdictColumn(r.outcome));
    if (t < s.truths.size() && v < s.verdicts.size()) ++s.confusion[t][v];
    if (!r.outcome.ok) {
      ++s.failures;
      continue;
    }
    if (r.truth == "control") {
      ++controls;
      flagged += r.detected ? 1 : 0;
      none += r.right ? 1 : 0;
      continue;
    }
    for (std::size_t b = 0; b + 1 < edges.size(); ++b) {
      if (r.strength_z >= edges[b] && r.strength_z < edges[b + 1]) {
        ++bin_n[b];
        bin_det[b] += r.detected ? 1 : 0;
        bin_right[b] += r.right ? 1 : 0;
      }
    }
    if (r.strength_class == "clear") {
      ++clear;
      clear_right += r.right ? 1 : 0;
      ++by_n[t];
      by_k[t] += r.right ? 1 : 0;
    }
    if (r.overlap >= 0) {
      ++overlap_n;
      overlap_k += r.overlap;
      contain_k += r.contain;
    }
    if (r.shrink > 0.0) {
      shrinks.push_back(r.shrink);
      five_or_level += r.shrink >= 5.0 || r.heldout_at_model_level ? 1 : 0;
    }
  }
  s.false_alarm = MakeProportion(flagged, controls);
  s.control_none = MakeProportion(none, controls);
  s.clear_right = MakeProportion(clear_right, clear);
  for (std::size_t t = 1; t < s.truths.size(); ++t) {
    s.clear_right_by_effect.emplace_back(s.truths[t], MakeProportion(by_k[t], by_n[t]));
  }
  for (std::size_t b = 0; b + 1 < edges.size(); ++b) {
    s.bins.push_back({edges[b], edges[b + 1], MakeProportion(bin_det[b], bin_n[b]), MakeProportion(bin_right[b], bin_n[b])});
  }
  s.overlap = MakeProportion(overlap_k, overlap_n);
  s.contain = MakeProportion(contain_k, overlap_n);
  s.shrink_count = static_cast<int>(shrinks.size());
  int five = 0;
  for (double x : shrinks) five += x >= 5.0 ? 1 : 0;
  s.shrink_5x = MakeProportion(five, s.shrink_count);
  s.shrink_5x_or_model_level = MakeProportion(five_or_level, s.shrink_count);
  if (!shrinks.empty()) {
    std::sort(shrinks.begin(), shrinks.end());
    const std::size_t n = shrinks.size();
    s.shrink_median = n % 2 ? shrinks[n / 2] : 0.5 * (shrinks[n / 2 - 1] + shrinks[n / 2]);
    s.shrink_min = shrinks.front();
  }
  return s;
}

}  // namespace allanlab::experiments
