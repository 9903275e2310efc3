#include "experiments/diagnosis/benchmark_report.h"

#include <algorithm>
#include <cstdio>

#include "common/number_text.h"

namespace allanlab::experiments {
namespace {

std::string Percent(const Proportion& p) {
  if (p.trials == 0) return "- (0 recordings)";
  char b[96];
  std::snprintf(b, sizeof b, "%d/%d = %.1f %% [%.1f, %.1f]", p.successes, p.trials, 100.0 * p.rate(),
                100.0 * p.low, 100.0 * p.high);
  return b;
}

std::string Joined(const std::vector<std::string>& v, const char* sep) {
  std::string out;
  for (const auto& x : v) {
    if (!out.empty()) out += sep;
    out += x;
  }
  return out;
}

std::string RegionsText(const BenchmarkOutcome& o) {
  std::string out;
  for (const auto& g : o.regions) {
    if (!out.empty()) out += ";";
    out += g.view;
    out += ':';
    out += SignificantDigits(g.tau_min_s, 4);
    out += '-';
    out += SignificantDigits(g.tau_max_s, 4);
  }
  return out;
}

std::string Tri(int v) { return v < 0 ? "" : (v ? "1" : "0"); }

}  // namespace

void WriteBenchmarkCsv(std::ostream& os, const std::string& provenance, const std::vector<BenchmarkRow>& rows) {
  os << provenance;
  os << "index,preset,rate_hz,samples,duration_s,truth,params,target_z,strength_z,oavar_z,kurtosis_z,"
        "halves_z,relative_peak,peak_tau_s,class,expected_tau_min_s,expected_tau_max_s,diagnosed,"
        "significant,threshold_z,verdict,also_consistent,regions,detected,right,overlap,contain,"
        "heldout_chi2_before,heldout_chi2_after,heldout_points,shrink,heldout_at_model_level\n";
  for (const BenchmarkRow& r : rows) {
    const BenchmarkOutcome& o = r.outcome;
    os << r.index << ',' << r.preset << ',' << SignificantDigits(r.rate_hz, 4) << ',' << r.num_samples << ','
       << SignificantDigits(static_cast<double>(r.num_samples) / r.rate_hz, 4) << ',' << r.truth << ",\"" << r.params << "\","
       << SignificantDigits(r.target_z, 4) << ',' << SignificantDigits(r.strength_z, 4) << ',' << SignificantDigits(r.oavar_z, 4) << ',' << SignificantDigits(r.kurtosis_z, 4) << ','
       << SignificantDigits(r.halves_z, 4) << ',' << SignificantDigits(r.relative_peak, 4) << ',' << SignificantDigits(r.peak_tau_s, 4) << ',' << r.strength_class << ','
       << SignificantDigits(r.expected_tau_min_s, 4) << ',' << SignificantDigits(r.expected_tau_max_s, 4) << ',' << (o.ok ? 1 : 0) << ','
       << (o.significant ? 1 : 0) << ',' << SignificantDigits(o.threshold_z, 4) << ',' << (o.ok ? o.verdict : "failed") << ",\""
       << Joined(o.also_consistent, ";") << "\",\"" << RegionsText(o) << "\"," << (r.detected ? 1 : 0) << ','
       << (r.right ? 1 : 0) << ',' << Tri(r.overlap) << ',' << Tri(r.contain) << ',';
    if (o.has_heldout) {
      os << SignificantDigits(o.heldout_before_chi2, 4) << ',' << SignificantDigits(o.heldout_after_chi2, 4) << ',' << o.heldout_points;
    } else {
      os << ",,";
    }
    os << ',' << (r.shrink > 0.0 ? SignificantDigits(r.shrink, 4) : "") << ',' << (r.shrink > 0.0 ? (r.heldout_at_model_level ? "1" : "0") : "")
       << '\n';
  }
}

std::vector<TargetCheck> CheckTargets(const BenchmarkSummary& s) {
  std::vector<TargetCheck> t;
  t.push_back({"false alarms on controls <= 5 % (upper bound <= 8 %)", Percent(s.false_alarm),
               s.false_alarm.trials > 0 && s.false_alarm.rate() <= 0.05 && s.false_alarm.high <= 0.08});
  t.push_back({"right effect (or also_consistent) on clear single effects >= 90 %", Percent(s.clear_right),
               s.clear_right.trials > 0 && s.clear_right.low >= 0.9});
  t.push_back({"held-out chi2 shrinks >= 5x on >= 90 % of right diagnoses",
               Percent(s.shrink_5x) + "; median " + SignificantDigits(s.shrink_median, 4) + "x, min " + SignificantDigits(s.shrink_min, 4) + "x",
               s.shrink_count > 0 && s.shrink_5x.low >= 0.9});
  t.push_back({"(held-out chi2 shrinks >= 5x, or ends within the model's own 95 % chi2 range)",
               Percent(s.shrink_5x_or_model_level), s.shrink_count > 0 && s.shrink_5x_or_model_level.low >= 0.9});
  return t;
}

void WriteBenchmarkMarkdown(std::ostream& os, const std::string& title, const std::string& description,
                            const std::string& provenance, const std::vector<BenchmarkRow>& rows,
                            const BenchmarkSummary& s) {
  os << "# " << title << "\n\n" << description << "\n\n";
  os << "## Targets\n\nA target is met only when its whole Wilson 95 % interval clears it.\n\n"
     << "| target | measured [95 % interval] | met |\n|---|---|---|\n";
  for (const TargetCheck& t : CheckTargets(s)) os << "| " << t.name << " | " << t.measured << " | " << (t.met ? "yes" : "no") << " |\n";
  os << "\n";
  if (s.failures > 0) os << "Recordings diagnose refused or failed on: " << s.failures << "\n\n";

  os << "## Confusion matrix (rows: true effect, columns: verdict)\n\n| true \\ verdict |";
  for (const auto& v : s.verdicts) os << ' ' << v << " |";
  os << "\n|---|";
  for (std::size_t i = 0; i < s.verdicts.size(); ++i) os << "---|";
  os << '\n';
  for (std::size_t t = 0; t < s.truths.size(); ++t) {
    os << "| " << s.truths[t] << " |";
    for (int n : s.confusion[t]) os << ' ' << (n ? std::to_string(n) : ".") << " |";
    os << '\n';
  }
  os << "\n## Controls\n\nfalse alarms (significant gap): " << Percent(s.false_alarm)
     << "; verdict none: " << Percent(s.control_none) << "\n\n";
  os << "## Detection and right effect vs strength (effect recordings)\n\n"
     << "| strength z | recordings | detected | right effect |\n|---|---|---|---|\n";
  for (const StrengthBin& b : s.bins) {
    os << "| [" << SignificantDigits(b.lo, 4) << ", " << (b.hi > 1e100 ? std::string("inf") : SignificantDigits(b.hi, 4)) << ") | " << b.detected.trials
       << " | " << Percent(b.detected) << " | " << Percent(b.right) << " |\n";
  }
  os << "\n## Right effect on clear single effects, per effect\n\n| effect | right |\n|---|---|\n";
  for (const auto& [id, p] : s.clear_right_by_effect) os << "| " << id << " | " << Percent(p) << " |\n";
  if (!s.not_drawn.empty()) os << "\nNot drawn in this run (no rate): " << Joined(s.not_drawn, ", ") << ".\n";
  os << "\n## Localization (detected effects with an expected tau range)\n\n"
     << "a reported region overlaps the expected range: " << Percent(s.overlap)
     << "\n\none reported region contains the expected range: " << Percent(s.contain) << "\n\n";
  os << "## Held-out gap shrinkage (right diagnoses)\n\n" << s.shrink_count
     << " recordings; chi2 before / after on the held-out half: median " << SignificantDigits(s.shrink_median, 4) << "x, min "
     << SignificantDigits(s.shrink_min, 4) << "x; >= 5x: " << Percent(s.shrink_5x)
     << "; >= 5x or after within the 95 % chi2 range of its points (the half as the model predicts, the gap "
        "having been too small for a 5x ratio): "
     << Percent(s.shrink_5x_or_model_level) << "\n\n";
  os << "## Recordings\n\n| # | preset | rate Hz | samples | truth | params | strength z (oavar/kurt/halves) "
        "| class | expected tau s | verdict | also consistent | regions | right | overlap/contain | held-out chi2 "
        "before -> after (points) |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const BenchmarkRow& r : rows) {
    const BenchmarkOutcome& o = r.outcome;
    os << "| " << r.index << " | " << r.preset << " | " << SignificantDigits(r.rate_hz, 4) << " | " << r.num_samples << " | " << r.truth
       << " | " << r.params << " | " << SignificantDigits(r.strength_z, 4) << " (" << SignificantDigits(r.oavar_z, 4) << "/" << SignificantDigits(r.kurtosis_z, 4) << "/"
       << SignificantDigits(r.halves_z, 4) << ") | " << r.strength_class << " | "
       << (r.expected_tau_min_s > 0 ? SignificantDigits(r.expected_tau_min_s, 4) + " - " + SignificantDigits(r.expected_tau_max_s, 4) : std::string("-"))
       << " | " << (o.ok ? o.verdict : "failed: " + o.failure) << " | " << Joined(o.also_consistent, ", ") << " | "
       << RegionsText(o) << " | " << (r.right ? "yes" : "no") << " | " << Tri(r.overlap) << "/" << Tri(r.contain)
       << " | ";
    if (o.has_heldout) {
      os << SignificantDigits(o.heldout_before_chi2, 4) << " -> " << SignificantDigits(o.heldout_after_chi2, 4) << " (" << o.heldout_points << ")";
    }
    os << " |\n";
  }
  os << "\n## Provenance\n\n" << provenance;
}

void WriteGeneratorComparison(std::ostream& os, const std::string& provenance,
                              const std::vector<std::pair<std::string, BenchmarkSummary>>& runs) {
  os << "# Diagnosis benchmark: generators side by side\n\n"
     << "The same diagnosis on recordings from each generator; a target is met only when its whole "
        "Wilson 95 % interval clears it. `sim`: sim/'s own generators (the code the candidate models "
        "share); `independent`: independent/, written apart from sim/ and from the candidates.\n\n| target |";
  for (const auto& [name, s] : runs) os << ' ' << name << " | met |";
  os << "\n|---|";
  for (std::size_t i = 0; i < runs.size(); ++i) os << "---|---|";
  os << "\n";
  std::vector<std::vector<TargetCheck>> checks;
  for (const auto& run : runs) checks.push_back(CheckTargets(run.second));
  for (std::size_t t = 0; !checks.empty() && t < checks.front().size(); ++t) {
    os << "| " << checks.front()[t].name << " |";
    for (const auto& c : checks) os << ' ' << c[t].measured << " | " << (c[t].met ? "yes" : "no") << " |";
    os << "\n";
  }
  os << "\n## Right effect on clear single effects, per effect\n\n| effect |";
  for (const auto& run : runs) os << ' ' << run.first << " |";
  os << "\n|---|";
  for (std::size_t i = 0; i < runs.size(); ++i) os << "---|";
  os << "\n";
  // Every effect either run drew; "not drawn" where a run has none of it.
  for (Effect effect : kAllEffects) {
    const std::string id(EffectId(effect));
    std::vector<std::string> cells;
    bool any = false;
    for (const auto& run : runs) {
      const auto& by = run.second.clear_right_by_effect;
      const auto it = std::find_if(by.begin(), by.end(), [&](const auto& x) { return x.first == id; });
      any |= it != by.end();
      cells.push_back(it != by.end() ? Percent(it->second) : std::string("not drawn"));
    }
    if (!any) continue;
    os << "| " << id << " |";
    for (const std::string& cell : cells) os << ' ' << cell << " |";
    os << "\n";
  }
  os << "\n## Provenance\n\n" << provenance;
}

void WriteInjectedSection(std::ostream& os, const std::vector<BenchmarkRow>& rows) {
  os << "## Real recordings with an injected effect\n\n";
  if (rows.empty()) {
    os << "None in this run.\n\n";
    return;
  }
  int named = 0, ran = 0;
  for (const BenchmarkRow& r : rows) {
    if (!r.outcome.ok) continue;
    ++ran;
    named += NamesEffect(r.outcome, r.truth) ? 1 : 0;
  }
  os << "The recording's own noise and effects stay (these are not controls); the injected effect is "
        "named (verdict, a member of a set verdict, or also consistent) in "
     << Percent(MakeProportion(named, ran)) << ".\n\n"
     << "| # | segment | samples | injected | params | strength z (oavar/kurt/block) | verdict | also consistent | named |\n"
        "|---|---|---|---|---|---|---|---|---|\n";
  for (const BenchmarkRow& r : rows) {
    const BenchmarkOutcome& o = r.outcome;
    os << "| " << r.index << " | " << r.preset << " | " << r.num_samples << " | " << r.truth << " | " << r.params
       << " | " << SignificantDigits(r.strength_z, 4) << " (" << SignificantDigits(r.oavar_z, 4) << "/" << SignificantDigits(r.kurtosis_z, 4) << "/" << SignificantDigits(r.halves_z, 4) << ") | "
       << (o.ok ? o.verdict : "failed: " + o.failure) << " | " << Joined(o.also_consistent, ", ") << " | "
       << (NamesEffect(o, r.truth) ? "yes" : "no") << " |\n";
  }
  os << "\n";
}

}  // namespace allanlab::experiments
