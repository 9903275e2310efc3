#include "experiments/diagnosis/benchmark_report.h"

#include <cstdio>

namespace allanlab::experiments {
namespace {

std::string G(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.4g", v);
  return b;
}

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
    out += G(g.tau_min_s);
    out += '-';
    out += G(g.tau_max_s);
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
    os << r.index << ',' << r.preset << ',' << G(r.rate_hz) << ',' << r.num_samples << ','
       << G(static_cast<double>(r.num_samples) / r.rate_hz) << ',' << r.truth << ",\"" << r.params << "\","
       << G(r.target_z) << ',' << G(r.strength_z) << ',' << G(r.oavar_z) << ',' << G(r.kurtosis_z) << ','
       << G(r.halves_z) << ',' << G(r.relative_peak) << ',' << G(r.peak_tau_s) << ',' << r.strength_class << ','
       << G(r.expected_tau_min_s) << ',' << G(r.expected_tau_max_s) << ',' << (o.ok ? 1 : 0) << ','
       << (o.significant ? 1 : 0) << ',' << G(o.threshold_z) << ',' << (o.ok ? o.verdict : "failed") << ",\""
       << Joined(o.also_consistent, ";") << "\",\"" << RegionsText(o) << "\"," << (r.detected ? 1 : 0) << ','
       << (r.right ? 1 : 0) << ',' << Tri(r.overlap) << ',' << Tri(r.contain) << ',';
    if (o.has_heldout) {
      os << G(o.heldout_before_chi2) << ',' << G(o.heldout_after_chi2) << ',' << o.heldout_points;
    } else {
      os << ",,";
    }
    os << ',' << (r.shrink > 0.0 ? G(r.shrink) : "") << ',' << (r.shrink > 0.0 ? (r.heldout_at_model_level ? "1" : "0") : "")
       << '\n';
  }
}

void WriteBenchmarkMarkdown(std::ostream& os, const std::string& provenance,
                            const std::vector<BenchmarkRow>& rows, const BenchmarkSummary& s) {
  os << "# Blind diagnosis benchmark (issue 6)\n\n"
     << "Each recording is drawn at random (sensor preset reduced to its IEEE 952 terms, length, rate, "
        "effect or none, strength), written as a file by `allanlab simulate`, and diagnosed by "
        "`allanlab diagnose` with its default settings, told nothing but the file's format, rate and "
        "unit. Strength is the expected peak gap z of the view that sees the effect (OAVAR against "
        "the best baseline fit; kurtosis for outliers and quantizers; halves for steps and drifts): "
        "see experiments/diagnosis/benchmark_case.h. Classes: weak < 2, borderline < 10, clear >= 10. "
        "Rates carry Wilson 95 % intervals.\n\n";
  os << "## Targets\n\n| target | measured | met |\n|---|---|---|\n";
  os << "| false alarms on controls <= 5 % | " << Percent(s.false_alarm) << " | "
     << (s.false_alarm.trials > 0 && s.false_alarm.rate() <= 0.05 ? "yes" : "no") << " |\n";
  os << "| right effect (or also_consistent) on clear single effects >= 90 % | " << Percent(s.clear_right)
     << " | " << (s.clear_right.trials > 0 && s.clear_right.rate() >= 0.9 ? "yes" : "no") << " |\n";
  os << "| held-out chi2 shrinks >= 5x on right diagnoses | " << Percent(s.shrink_5x) << "; median "
     << G(s.shrink_median) << "x, min " << G(s.shrink_min) << "x | "
     << (s.shrink_count > 0 && s.shrink_5x.successes == s.shrink_count ? "yes" : "no") << " |\n";
  os << "| (held-out chi2 shrinks >= 5x, or ends within the model's own 95 % chi2 range) | "
     << Percent(s.shrink_5x_or_model_level) << " | "
     << (s.shrink_count > 0 && s.shrink_5x_or_model_level.successes == s.shrink_count ? "yes" : "no") << " |\n\n";
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
    os << "| [" << G(b.lo) << ", " << (b.hi > 1e100 ? std::string("inf") : G(b.hi)) << ") | " << b.detected.trials
       << " | " << Percent(b.detected) << " | " << Percent(b.right) << " |\n";
  }
  os << "\n## Right effect on clear single effects, per effect\n\n| effect | right |\n|---|---|\n";
  for (const auto& [id, p] : s.clear_right_by_effect) os << "| " << id << " | " << Percent(p) << " |\n";
  os << "\n## Localization (detected effects with an expected tau range)\n\n"
     << "a reported region overlaps the expected range: " << Percent(s.overlap)
     << "\n\none reported region contains the expected range: " << Percent(s.contain) << "\n\n";
  os << "## Held-out gap shrinkage (right diagnoses)\n\n" << s.shrink_count
     << " recordings; chi2 before / after on the held-out half: median " << G(s.shrink_median) << "x, min "
     << G(s.shrink_min) << "x; >= 5x: " << Percent(s.shrink_5x)
     << "; >= 5x or after within the 95 % chi2 range of its points (the half as the model predicts, the gap "
        "having been too small for a 5x ratio): "
     << Percent(s.shrink_5x_or_model_level) << "\n\n";
  os << "## Recordings\n\n| # | preset | rate Hz | samples | truth | params | strength z (oavar/kurt/halves) "
        "| class | expected tau s | verdict | also consistent | regions | right | overlap/contain | held-out chi2 "
        "before -> after (points) |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const BenchmarkRow& r : rows) {
    const BenchmarkOutcome& o = r.outcome;
    os << "| " << r.index << " | " << r.preset << " | " << G(r.rate_hz) << " | " << r.num_samples << " | " << r.truth
       << " | " << r.params << " | " << G(r.strength_z) << " (" << G(r.oavar_z) << "/" << G(r.kurtosis_z) << "/"
       << G(r.halves_z) << ") | " << r.strength_class << " | "
       << (r.expected_tau_min_s > 0 ? G(r.expected_tau_min_s) + " - " + G(r.expected_tau_max_s) : std::string("-"))
       << " | " << (o.ok ? o.verdict : "failed: " + o.failure) << " | " << Joined(o.also_consistent, ", ") << " | "
       << RegionsText(o) << " | " << (r.right ? "yes" : "no") << " | " << Tri(r.overlap) << "/" << Tri(r.contain)
       << " | ";
    if (o.has_heldout) {
      os << G(o.heldout_before_chi2) << " -> " << G(o.heldout_after_chi2) << " (" << o.heldout_points << ")";
    }
    os << " |\n";
  }
  os << "\n## Provenance\n\n" << provenance;
}

}  // namespace allanlab::experiments
