#include "app/commands/diagnose_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>
#include <omp.h>

#include "app/reports/allan_plot.h"
#include "common/atomic_file.h"
#include "app/input/record_curve.h"
#include "app/input/constant_stretch.h"
#include "app/input/curve_table.h"
#include "app/reports/diagnose_html.h"
#include "app/reports/diagnose_plot.h"
#include "app/reports/diagnose_progress.h"
#include "app/reports/diagnose_summary.h"
#include "app/reports/output_paths.h"
#include "app/reports/provenance.h"
#include "app/reports/sensor_coefficients.h"
#include "app/input/record_reader.h"
#include "sim/sensor_spec.h"
#include "estimators/fit/noise_coefficient.h"
#include "experiments/diagnosis/diagnose.h"
#include "experiments/diagnosis/envelope.h"
#include "common/number_text.h"

namespace allanlab::app {
namespace {

constexpr const char* kCommand = "diagnose";
using Failure = CommandFailure;
using estimators::Coefficient;
using namespace allanlab::experiments;
using Json = nlohmann::ordered_json;

bool ParseModel(const std::string& text, std::vector<Coefficient>* terms, std::string* why) {
  std::stringstream ss(text);
  std::string id;
  while (std::getline(ss, id, ',')) {
    Coefficient c;
    if (!estimators::ParseCoefficient(id, &c)) {
      *why = "unknown term '" + id + "' (expected a comma list of Q, N, B, K, R)";
      return false;
    }
    terms->push_back(c);
  }
  if (terms->empty()) {
    *why = "no terms";
    return false;
  }
  return true;
}

// The baseline the options ask for (DiagnoseOptions::baseline) into *d, and its description for
// the provenance.
std::optional<Failure> BaselineOptions(const DiagnoseCommandOptions& o, DiagnoseOptions* d) {
  std::string why;
  const bool sensor = !o.sensor_path.empty() || !o.preset.empty();
  if (!o.sensor_path.empty() && !o.preset.empty()) return UsageFailure("give --sensor or --preset, not both");
  if (sensor && o.model) {
    return UsageFailure("--model and --" + std::string(o.preset.empty() ? "sensor" : "preset") +
                        " contradict: the sensor model fixes the terms (use --float LIST to refit some of its coefficients)");
  }
  if (!sensor && !o.float_terms.empty()) return UsageFailure("--float needs --sensor SPEC.yaml or --preset NAME");
  d->terms.clear();
  if (sensor) {
    d->baseline = DiagnoseOptions::Baseline::kSensor;
    if (!o.preset.empty()) {
      const std::vector<std::string> names = sim::PresetNames();
      if (std::find(names.begin(), names.end(), o.preset) == names.end()) {
        std::string known;
        for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
        return UsageFailure("unknown preset '" + o.preset + "' (known: " + known + ")");
      }
      if (!sim::LoadPreset(o.preset, &d->sensor, &why)) return RuntimeFailure("preset " + o.preset + ": " + why);
    } else if (!sim::LoadSensorModelFile(o.sensor_path, &d->sensor, &why)) {
      return RuntimeFailure(why);
    }
    if (!o.float_terms.empty() && !ParseModel(o.float_terms, &d->terms, &why)) return UsageFailure("--float: " + why);
    return std::nullopt;
  }
  if (o.model) {
    d->baseline = DiagnoseOptions::Baseline::kTerms;
    if (!ParseModel(*o.model, &d->terms, &why)) return UsageFailure("--model: " + why);
    return std::nullopt;
  }
  d->baseline = DiagnoseOptions::Baseline::kFit;
  d->terms = {Coefficient::kQ, Coefficient::kN, Coefficient::kB, Coefficient::kK, Coefficient::kR};
  return std::nullopt;
}

std::string BaselineDescription(const DiagnoseCommandOptions& o) {
  if (!o.preset.empty() || !o.sensor_path.empty()) {
    return (o.preset.empty() ? "sensor " + o.sensor_path : "preset " + o.preset) + " held" +
           (o.float_terms.empty() ? "" : ", " + o.float_terms + " refitted");
  }
  if (o.model) return "terms " + *o.model + " fitted (no band-limit)";
  return "as allanlab fit: Q,N,B,K,R fitted, plus a band-limit when the curve shows one";
}

Json MetricsJson(const GapMetrics& m) {
  return Json{{"chi2", m.chi2}, {"points", m.points}, {"percent_in_95", 100.0 * m.fraction_in_95},
              {"max_abs_z", m.max_abs_z}};
}

Json GapJson(const ModelGap& g) {
  Json j = Json::object();
  for (const ViewResiduals& v : g.views) j[std::string(ViewId(v.view))] = MetricsJson(Metrics(v.z));
  j["all"] = MetricsJson(g.All());
  return j;
}

Json ParamsJson(const std::vector<EffectInstance>& effects, const DiagnoseUnits& units) {
  auto one = [&](const EffectInstance& e) {
    Json p = Json::object();
    for (const std::string& name : EffectParameterNames(e.effect)) p[ParameterName(units, name)] = e.params.at(name);
    if (const std::string family = FilterFamilyName(e); !family.empty()) p["filter"] = family;
    if (HasSubtractiveDither(e)) p["dither"] = "subtractive";
    return p;
  };
  if (effects.size() == 1) return one(effects[0]);
  Json j = Json::object();
  for (const auto& e : effects) j[std::string(EffectId(e.effect))] = one(e);
  return j;
}

// The same parameters in the report's units, as `summary.effects` gives the verdict's (one entry
// per effect).
Json ReportedParamsJson(const std::vector<EffectInstance>& effects, const DiagnoseUnits& units, SampleClock sample_clock) {
  Json j = Json::array();
  for (const auto& e : effects) j.push_back(PlainEffectJson(MakePlainEffect(e, units, sample_clock)));
  return j;
}

Json CoefficientsJson(const estimators::FitSummary& fit, const DiagnoseUnits& units) {
  Json j = Json::object();
  for (Coefficient c : estimators::kAllCoefficients) {
    const auto& e = fit.at(c);
    if (!e.asked) continue;
    j[std::string(estimators::CoefficientId(c))] = {
        {"value", e.fitted ? CoefficientValue(units, c, e.value_si) : 0.0},
        {"sigma", CoefficientValue(units, c, e.sigma_si)},
        {"unit", CoefficientUnit(units, c)},
        {"fitted", e.fitted},
        {"upper_limit", !e.fitted && e.has_upper_limit ? Json(CoefficientValue(units, c, e.upper_limit_si)) : Json(nullptr)}};
  }
  return j;
}

Json RegionsJson(const std::vector<GapRegion>& found) {
  Json regions = Json::array();
  for (const GapRegion& r : found) {
    Json region{{"view", std::string(ViewId(r.view))}};
    if (r.view == View::kPsd) {
      region["tau_min_s"] = 1.0 / (2.0 * r.x_max);
      region["tau_max_s"] = 1.0 / (2.0 * r.x_min);
      region["frequency_min_hz"] = r.x_min;
      region["frequency_max_hz"] = r.x_max;
    } else {
      region["tau_min_s"] = r.x_min;  // block-mean views: the block lengths
      region["tau_max_s"] = r.x_max;
    }
    if (r.view == View::kChangePoint) region["time_s"] = r.time_s;
    if (r.view == View::kTrend) region["time_constant_s"] = r.time_s;
    region["max_abs_z"] = r.max_abs_z;
    region["mean_z"] = r.mean_z;
    regions.push_back(region);
  }
  return regions;
}

// The models scored on a second recording: OAVAR ("baseline", "with_ID", as before) and every
// view with the shrink baseline / candidate chi2.
Json ValidationJson(const std::string& path, const ValidationScores& scores) {
  auto metrics = [](const std::optional<GapMetrics>& m) { return m ? MetricsJson(*m) : Json(nullptr); };
  Json v = {{"file", path}, {"baseline", metrics(scores.baseline)}};
  if (scores.candidate_id.empty()) return v;
  v["with_" + scores.candidate_id] = metrics(scores.candidate);
  v["model"] = scores.candidate_id;
  Json views = Json::object();
  for (const ViewResiduals& b : scores.baseline_views) {
    for (const ViewResiduals& c : scores.candidate_views) {
      if (c.view != b.view) continue;
      const GapMetrics mb = Metrics(b.z), mc = Metrics(c.z);
      views[std::string(ViewId(b.view))] = {{"baseline", MetricsJson(mb)}, {"model", MetricsJson(mc)},
                                             {"shrink", mc.chi2 > 0.0 ? mb.chi2 / mc.chi2 : 0.0}};
    }
  }
  v["views"] = views;
  return v;
}

void WriteValidation(std::ostream& os, const Json& v, bool markdown) {
  os << (markdown ? "\n## " : "") << "validation on " << v["file"].get<std::string>() << "\n";
  if (!v.contains("views")) {
    os << (markdown ? "\n" : "  ") << "no candidate to score\n";
    return;
  }
  if (markdown) os << "\n| view | points | chi2 baseline | chi2 with " << v["model"].get<std::string>() << " | shrink |\n|---|---|---|---|---|\n";
  for (const auto& [view, m] : v["views"].items()) {
    const double b = m["baseline"]["chi2"], c = m["model"]["chi2"];
    if (markdown) {
      os << "| " << view << " | " << m["baseline"]["points"] << " | " << SignificantDigits(b, 4) << " | " << SignificantDigits(c, 4) << " | "
         << SignificantDigits(m["shrink"].get<double>(), 4) << " |\n";
    } else {
      os << "  " << view << ": chi2 " << SignificantDigits(b, 4) << " -> " << SignificantDigits(c, 4) << " with " << v["model"].get<std::string>()
         << " (" << SignificantDigits(m["shrink"].get<double>(), 4) << "x)\n";
    }
  }
}

// The diagnosis's notes, then the value grid's step (when the samples sit on one) in the
// report's units and the record's.
std::vector<std::string> ReportNotes(const DiagnosisSummary& s, const DiagnoseUnits& unit) {
  std::vector<std::string> notes = s.notes;
  if (std::isfinite(s.value_grid_rad_per_s)) {
    const ReportedRate r = ReportRate(unit, s.value_grid_rad_per_s);
    notes.push_back("value grid step: " + SignificantDigits(r.value, 4) + " " + r.unit +
                    (r.record_value ? " (" + SignificantDigits(*r.record_value, 4) + " " + r.record_unit + ")" : ""));
  }
  return notes;
}

}  // namespace

Json DiagnosisJson(const DiagnosisSummary& s, const Provenance& p, const Json& validation,
                   const DiagnoseUnits& unit) {
  Json j;
  j["summary"] = PlainJson(MakePlainSummary(s, unit));
  const Json regions = RegionsJson(s.regions);
  j["gap"] = {{"significant", s.significant}, {"regions", regions}, {"threshold_z", s.threshold},
              {"points", s.total_points}, {"views", GapJson(s.before)}};
  if (s.before.has_heldout) j["gap"]["heldout"] = MetricsJson(s.before.heldout);
  Json verdict{{"effect", s.verdict}};
  verdict["params"] = Json::object();
  verdict["params_reported"] = Json::array();
  if (s.verdict_candidate >= 0 && s.verdict != "unexplained") {
    verdict["params"] = ParamsJson(s.candidates[s.verdict_candidate].effects, unit);
    verdict["params_reported"] = ReportedParamsJson(s.candidates[s.verdict_candidate].effects, unit, s.sample_clock);
  }
  Json also = Json::array(), separating = Json::object();
  for (const auto& a : s.also_consistent) {
    also.push_back(a.effect);
    if (!a.separating_view.empty()) separating[a.effect] = a.separating_view;
  }
  verdict["also_consistent"] = also;
  verdict["separating_views"] = separating;
  if (s.verdict == "unexplained" && s.verdict_candidate >= 0) {
    verdict["best_tried"] = s.candidates[s.verdict_candidate].id();
  }
  if (s.significant) verdict["explains"] = s.verdict == "unexplained" ? "none" : (s.explains_all ? "all" : "part");
  if (s.verdict_candidate >= 0) {
    Json steps = Json::array();
    for (const auto& st : s.candidates[s.verdict_candidate].steps) {
      Json step = {{"added", std::string(EffectId(st.added))},
                   {"heldout_chi2_before", st.heldout_before.chi2},
                   {"heldout_chi2_after", st.heldout_after.chi2},
                   {"heldout_points", st.heldout_after.points}};
      if (st.own_views_after.points > 0) {
        step["heldout_chi2_own_views_before"] = st.own_views_before.chi2;
        step["heldout_chi2_own_views_after"] = st.own_views_after.chi2;
        step["heldout_own_views_points"] = st.own_views_after.points;
      }
      steps.push_back(step);
    }
    verdict["steps"] = steps;
    verdict["remaining"] = RegionsJson(s.remaining);
  }
  j["verdict"] = verdict;
  Json candidates = Json::array();
  for (const CandidateResult& c : s.candidates) {
    Json cj{{"effect", c.id()},
            {"params", ParamsJson(c.effects, unit)},
            {"params_reported", ReportedParamsJson(c.effects, unit, s.sample_clock)}};
    cj["gap_before"] = GapJson(s.before);
    cj["gap_after"] = GapJson(c.after);
    cj["heldout_gap_before"] = c.after.has_heldout ? MetricsJson(c.heldout_before) : Json(nullptr);
    cj["heldout_gap_after"] = c.after.has_heldout ? MetricsJson(c.after.heldout) : Json(nullptr);
    if (c.after.has_heldout) {
      cj["heldout_scored_half"] = c.heldout_half == 0 ? "first" : "second";
      cj["heldout_views"] = c.heldout_in_gap_views ? "gap_views" : "oavar";
    }
    cj["score"] = c.score;
    cj["full_score"] = c.full_score;
    cj["monte_carlo_views"] = c.full_views;
    cj["closes_gap"] = c.closes_gap;
    if (!c.why_not_verdict.empty()) cj["not_the_verdict_because"] = c.why_not_verdict;
    cj["coefficients"] = CoefficientsJson(c.fit, unit);
    candidates.push_back(cj);
  }
  j["candidates"] = candidates;
  Json skipped = Json::array();
  for (const auto& k : s.skipped) skipped.push_back({{"effect", std::string(EffectId(k.effect))}, {"reason", k.reason}});
  j["skipped"] = skipped;
  Json band_limit = nullptr;
  if (s.baseline_model.band_limit.enabled()) {
    const auto& b = s.baseline_model.band_limit;
    band_limit = {{"order", b.kind == sim::LowPassKind::kFirstOrder ? 1 : 2},
                  {"cutoff_hz", b.cutoff_hz},
                  {"sampling", b.sampling == sim::OutputSampling::kAverage ? "average" : "point"}};
  }
  // What the baseline is: the IEEE terms fitted ("terms", --model), what allanlab fit reports
  // ("fit", the default) or the user's sensor model ("sensor", --sensor / --preset).
  const char* source = s.baseline_source == DiagnoseOptions::Baseline::kSensor ? "sensor"
                       : s.baseline_source == DiagnoseOptions::Baseline::kFit  ? "fit"
                                                                                 : "terms";
  j["baseline"] = {{"source", source}, {"coefficients", CoefficientsJson(s.baseline, unit)}, {"band_limit", band_limit},
                   {"fit", {{"chi2", s.baseline.gof_chi2}, {"dof", s.baseline.dof}, {"converged", s.baseline.converged}}}};
  if (!validation.is_null()) j["validation"] = validation;
  if (s.line_drift) {
    const LineDrift& d = *s.line_drift;
    j["line_drift"] = {{"line_hz", s.line_drift_frequency_hz},
                       {"blocks", kLineDriftBlocks},
                       {"block_s", d.block_s},
                       {"frequency_first_hz", d.frequency_hz.first},
                       {"frequency_last_hz", d.frequency_hz.last},
                       {"frequency_t", d.frequency_hz.t},
                       {"power_first_rad2_per_s2", d.power.first},
                       {"power_last_rad2_per_s2", d.power.last},
                       {"power_t", d.power.t},
                       {"t_threshold", kLineDriftT},
                       {"drifts", d.FrequencyDrifts() || d.PowerDrifts()}};
  }
  j["notes"] = ReportNotes(s, unit);
  j["provenance"] = ProvenanceJson(p);
  return j;
}

namespace {

// A table cell's text: its "|" (as in "|z|") escaped, which would otherwise end the cell.
std::string MarkdownCell(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '|') out += '\\';
    out += c;
  }
  return out;
}

// How a gap region departs: the record above or below the model, or for the block-mean views
// (x: block length) the step's time or the settling's time constant.
std::string RegionMeaning(const GapRegion& r, const DiagnoseUnits& unit) {
  if (r.view == View::kChangePoint) {
    return " (blocks; the " + QuantityWord(unit) + (r.mean_z > 0 ? " level rises" : " level falls") + " at t = " +
           SignificantDigits(r.time_s, 4) + " s from the start)";
  }
  if (r.view == View::kTrend) {
    return " (blocks; the " + QuantityWord(unit) + (r.mean_z > 0 ? " settles from above" : " settles from below") +
           " from the start, time constant " + SignificantDigits(r.time_s, 4) + " s)";
  }
  return r.mean_z > 0 ? " (record above model)" : " (record below model)";
}

// The report: the plain-words summary (diagnose_summary.h; left out with plain = false, for the
// HTML page that shows it itself), then the detail.
void WriteText(std::ostream& os, const DiagnosisSummary& s, bool markdown, const DiagnoseUnits& unit = {},
               bool plain = true) {
  const std::string h = markdown ? "## " : "";
  const PlainSummary summary = MakePlainSummary(s, unit);
  if (markdown && plain) os << "# allanlab diagnose\n\n";
  if (plain && markdown) {
    WritePlainMarkdown(os, summary);
  } else if (plain) {
    WritePlainText(os, summary);
    os << "\n";
  }
  os << h << "verdict: " << s.verdict;
  if (s.verdict_candidate >= 0) {
    const auto& c = s.candidates[s.verdict_candidate];
    os << (s.verdict == "unexplained" ? " (best tried: " + c.id() + ")" : "");
    for (std::size_t i = 0; i < c.effects.size() && i < summary.effects.size(); ++i) {
      os << "\n  " << EffectLabel(c.effects[i]) << ": " << QuantitiesText(summary.effects[i]);
    }
  }
  os << "\n";
  if (s.verdict_candidate >= 0) {
    const auto& c = s.candidates[s.verdict_candidate];
    if (s.verdict != "unexplained" && !s.explains_all) os << "  explains most of the gap, not all (what remains is below)\n";
    if (c.steps.size() > 1 || (s.verdict != "unexplained" && !c.steps.empty())) {
      for (const auto& st : c.steps) {
        os << (markdown ? "- " : "  ") << "adds " << EffectId(st.added) << ": held-out chi2 " << SignificantDigits(st.heldout_before.chi2, 4)
           << " -> " << SignificantDigits(st.heldout_after.chi2, 4) << " (" << st.heldout_after.points << " points)";
        if (st.own_views_after.points > 0) {
          os << "; in the views it shows in " << SignificantDigits(st.own_views_before.chi2, 4) << " -> "
             << SignificantDigits(st.own_views_after.chi2, 4) << " (" << st.own_views_after.points << " points)";
        }
        os << "\n";
      }
    }
    for (const GapRegion& r : s.remaining) {
      os << (markdown ? "- " : "  ") << "remains: " << ViewId(r.view) << " " << SignificantDigits(r.x_min, 4) << " .. " << SignificantDigits(r.x_max, 4)
         << (r.view == View::kPsd ? " Hz" : " s") << ", max |z| " << SignificantDigits(r.max_abs_z, 4)
         << (r.mean_z > 0 ? " (record above model)" : " (record below model)") << "\n";
    }
  }
  for (const auto& a : s.also_consistent) {
    os << "  also consistent: " << a.effect
       << (a.separating_view.empty() ? "" : " (the " + a.separating_view + " view could separate them)") << "\n";
  }
  if (s.baseline_model.band_limit.enabled()) {
    const auto& b = s.baseline_model.band_limit;
    os << "  baseline band-limit: " << (b.kind == sim::LowPassKind::kFirstOrder ? "first order" : "2nd-order Butterworth")
       << ", cutoff " << SignificantDigits(b.cutoff_hz, 4) << " Hz (held)\n";
  }
  if (markdown) os << "\n";
  os << h << "gap: " << (s.significant ? "significant" : "none") << " (|z| > " << SignificantDigits(s.threshold, 4)
     << ", Bonferroni over " << s.total_points << " points)\n";
  if (markdown) os << "\n| view | points | chi2 | % inside 95 % | max abs z |\n|---|---|---|---|---|\n";
  for (const ViewResiduals& v : s.before.views) {
    const GapMetrics m = Metrics(v.z);
    if (markdown) {
      os << "| " << ViewId(v.view) << " | " << m.points << " | " << SignificantDigits(m.chi2, 4) << " | "
         << SignificantDigits(100 * m.fraction_in_95, 4) << " | " << SignificantDigits(m.max_abs_z, 4) << " |\n";
    } else {
      os << "  " << ViewId(v.view) << ": chi2 " << SignificantDigits(m.chi2, 4) << " on " << m.points
         << " points, " << SignificantDigits(100 * m.fraction_in_95, 4) << " % inside 95 %, max |z| "
         << SignificantDigits(m.max_abs_z, 4) << "\n";
    }
  }
  for (const GapRegion& r : s.regions) {
    os << (markdown ? "- " : "  ") << "region " << ViewId(r.view) << " " << SignificantDigits(r.x_min, 4) << " .. "
       << SignificantDigits(r.x_max, 4) << (r.view == View::kPsd ? " Hz" : " s") << ", max |z| " << SignificantDigits(r.max_abs_z, 4)
       << RegionMeaning(r, unit) << "\n";
  }
  if (markdown && !s.candidates.empty()) {
    os << "\n" << h << "candidates\n\nscore: chi2 improvement - 2k on the views scored (k the effect's parameters)\n\n"
       << "| effect | views scored | score | OAVAR chi2 after | all chi2 after | max abs z after | held-out chi2 before -> after | closes | not the verdict because |\n"
       << "|---|---|---|---|---|---|---|---|---|\n";
  } else if (!s.candidates.empty()) {
    os << "candidates (score: chi2 improvement - 2k on the views scored, k the effect's parameters):\n";
  }
  for (const CandidateResult& c : s.candidates) {
    const std::string held = c.after.has_heldout ? SignificantDigits(c.heldout_before.chi2, 4) + " -> " +
                                                       SignificantDigits(c.after.heldout.chi2, 4) + " (" +
                                                       (c.heldout_half == 0 ? "first" : "second") + " half, " +
                                                       (c.heldout_in_gap_views ? "views with a gap" : "OAVAR") + ")"
                                                 : "-";
    const double score = c.full_views ? c.full_score : c.score;
    const std::string views = c.full_views ? "all" : "OAVAR only";
    if (markdown) {
      os << "| " << c.id() << " | " << views << " | " << SignificantDigits(score, 4) << " | "
         << SignificantDigits(c.after.View(View::kOavar).chi2, 4) << " | " << SignificantDigits(c.after.All().chi2, 4)
         << " | " << SignificantDigits(c.after.All().max_abs_z, 4) << " | " << held << " | "
         << (c.closes_gap ? "yes" : "no") << " | "
         << (s.verdict_candidate >= 0 && &c == &s.candidates[s.verdict_candidate] && s.verdict != "unexplained"
                 ? "(the verdict)"
                 : MarkdownCell(c.why_not_verdict))
         << " |\n";
    } else {
      os << "  " << c.id() << ": score " << SignificantDigits(score, 4) << " (" << views << "), max |z| after "
         << SignificantDigits(c.after.All().max_abs_z, 4) << ", held-out chi2 " << held
         << (c.closes_gap ? ", closes the gap" : "")
         << (c.why_not_verdict.empty() ? "" : "\n      not the verdict: " + c.why_not_verdict) << "\n";
    }
  }
  for (const auto& k : s.skipped) os << (markdown ? "- " : "  ") << "not tried: " << EffectId(k.effect) << " (" << k.reason << ")\n";
  for (const auto& n : ReportNotes(s, unit)) os << (markdown ? "- " : "  ") << "note: " << n << "\n";
}

}  // namespace

std::optional<CommandFailure> MakeDiagnoseOptions(const DiagnoseCommandOptions& o, DiagnoseOptions* d) {
  if (auto f = BaselineOptions(o, d)) return f;
  d->trials = o.trials;
  d->seed = o.seed;
  d->false_alarm = o.false_alarm;
  std::string why;
  if (!d->IsValid(&why)) return UsageFailure(why);
  return std::nullopt;
}

namespace {

// The diagnosis settings, for the provenance.
void AddDiagnosisSettings(const DiagnoseCommandOptions& o, Provenance* p) {
  p->Add("baseline", BaselineDescription(o));
  if (o.model) p->Add("model", *o.model);
  p->Add("trials", std::to_string(o.trials));
  p->Add("seed", std::to_string(o.seed));
  p->Add("false_alarm", ShortestDecimal(o.false_alarm));
}

// The plot's PNG for the HTML page: the --plot file's (already rendered into `png`), else
// rendered into a temporary next to the page and removed.
bool PlotBytes(const std::vector<AllanPlot>& panels, AtomicFile* png, const std::string& html_path,
               std::string* bytes, std::string* why) {
  AtomicFile scratch;
  AtomicFile* from = png;
  if (!png->is_open()) {
    if (!scratch.Open(html_path + ".png", why) || !RenderAllanPlotGrid(panels, 2, &scratch, why)) return false;
    from = &scratch;
  }
  std::ifstream in(from->temp_path(), std::ios::binary);
  std::ostringstream data;
  data << in.rdbuf();
  *bytes = data.str();
  if (bytes->empty()) {
    *why = "the plot for the HTML page is empty";
    return false;
  }
  return true;
}

std::vector<std::pair<std::string, std::string>> ProvenancePairs(const Provenance& p) {
  std::vector<std::pair<std::string, std::string>> out(p.fields.begin(), p.fields.end());
  out.emplace_back("command", p.command_line);
  out.emplace_back("git", p.git_sha);
  return out;
}

// Several columns of one record (gyro and accelerometer axes): a diagnosis each, one JSON and
// report with a section per column, one PNG with a panel per column. Each is reported in its
// sensor's units (app/reports/diagnose_units.h).
std::optional<Failure> DiagnoseSeveral(const DiagnoseCommandOptions& o, const DiagnoseOptions& d,
                                       const std::string& command_line, AtomicFile* json, AtomicFile* report,
                                       AtomicFile* png, AtomicFile* html) {
  std::string why;
  std::vector<std::vector<double>> rates;
  RecordInfo info;
  if (const int code = ReadRatesFromFile(o.record, kCommand, &rates, &info, &why); code != kExitOk) {
    return Failure{code, why};
  }
  if (d.baseline == DiagnoseOptions::Baseline::kSensor) {
    for (const ColumnInfo& c : info.columns) {
      if (c.sensor == ImuSensor::kAccelerometer) {
        return UsageFailure(info.path + ": " + c.name + " is an accelerometer axis; --preset and --sensor describe a "
                            "gyro: diagnose it against its fitted model (no --preset/--sensor) or drop it from --columns");
      }
    }
  }
  Provenance p = MakeProvenance(kCommand, command_line);
  p.Add("input", info.path);
  std::string columns;
  for (const ColumnInfo& c : info.columns) {
    columns += (columns.empty() ? "" : ", ") + c.name + " " + c.units + " (" + c.units_source + ")";
  }
  p.Add("columns", columns);
  p.Add("sample_rate", ShortestDecimal(info.sample_clock.rate_hz()) + " Hz (" + info.rate_source + ")");
  p.Add("samples", std::to_string(info.samples));
  if (info.dropped_nonfinite > 0) p.Add("dropped_nonfinite", std::to_string(info.dropped_nonfinite));
  AddDiagnosisSettings(o, &p);
  Json entries = Json::array();
  std::vector<AllanPlot> panels;
  std::vector<HtmlSection> sections;
  std::ostringstream markdown;
  for (std::size_t i = 0; i < info.columns.size(); ++i) {
    const ColumnInfo& c = info.columns[i];
    DiagnosisSummary s;
    DiagnoseProgress progress(c.name, !o.quiet, o.progress);
    DiagnoseOptions with_progress = d;
    with_progress.progress = [&](std::string_view stage, int done, int total) { progress.Update(stage, done, total); };
    const bool diagnosed = DiagnoseRecord(with_progress, rates[i], info.sample_clock, &s);
    progress.Clear();
    if (!diagnosed) {
      return RuntimeFailure(info.path + ": column " + c.name + ": " + s.message);
    }
    if (const auto stuck = DescribeConstantStretch(c.longest_constant_stretch, info.samples, info.sample_clock.rate_hz())) {
      s.notes.push_back("record: " + *stuck);
    }
    const DiagnoseUnits unit{c.sensor, c.units};
    const std::string heading = "# column " + c.name + " (" + std::string(ImuSensorName(c.sensor)) + ", " + c.units + ")";
    std::cout << (i ? "\n" : "") << heading << "\n";
    if (c.sensor == ImuSensor::kAccelerometer) std::cout << AccelerometerTermsLine() << "\n";
    WriteText(std::cout, s, false, unit);
    Json one = DiagnosisJson(s, p, Json(), unit);
    one.erase("provenance");
    Json entry = {{"column", c.name}, {"sensor", std::string(ImuSensorName(c.sensor))}, {"units", c.units}};
    entry.update(one);
    entries.push_back(std::move(entry));
    markdown << (i ? "\n" : "") << heading << "\n\n";
    WriteText(markdown, s, true, unit);
    for (AllanPlot& panel : DiagnosePanels(s, "allanlab diagnose: " + info.path + ", " + c.name, unit)) {
      panels.push_back(std::move(panel));
    }
    std::ostringstream detail;
    WriteText(detail, s, true, unit, false);
    sections.push_back({"column " + c.name, MakePlainSummary(s, unit), detail.str()});
  }
  std::cout.flush();
  if (json->is_open()) json->stream() << Json{{"provenance", ProvenanceJson(p)}, {"columns", entries}}.dump(2) << "\n";
  if (report->is_open()) {
    report->stream() << markdown.str() << "\n## provenance\n\n";
    for (const auto& [k, v] : p.fields) report->stream() << "- " << k << ": " << v << "\n";
    report->stream() << "- command: `" << p.command_line << "`\n- git: " << p.git_sha << "\n";
  }
  if (png->is_open() && !RenderAllanPlotGrid(panels, 2, png, &why)) return RuntimeFailure(why);
  if (html->is_open()) {
    std::string bytes;
    if (!PlotBytes(panels, png, html->path(), &bytes, &why)) return RuntimeFailure(why);
    WriteDiagnoseHtml(html->stream(), "allanlab diagnose: " + info.path, sections, bytes, ProvenancePairs(p));
  }
  for (AtomicFile* file : {json, report, png, html}) {
    if (file->is_open() && !file->Commit(&why)) return RuntimeFailure(why);
  }
  return std::nullopt;
}

std::optional<Failure> Diagnose(const DiagnoseCommandOptions& o, const std::string& command_line) {
  std::string why;
  DiagnoseOptions d;
  if (auto f = MakeDiagnoseOptions(o, &d)) return f;
  if (o.jobs < 0 || o.jobs > 256) return UsageFailure("--jobs must be in [1, 256] (0 or unset: every core)");
  if (o.jobs > 0) omp_set_num_threads(o.jobs);
  const bool curve_mode = !o.curve.path.empty();
  if (curve_mode && !o.record.path.empty()) return UsageFailure("give FILE or --curve, not both");
  if (!curve_mode && o.record.path.empty()) return UsageFailure("FILE (or --curve) is required");
  CurveTable table;
  if (curve_mode) {
    if (const int code = ReadCurveFromOptions(o.curve, o.record.rate_hz, &table, &why); code != kExitOk) {
      return Failure{code, why};
    }
  }
  std::vector<std::pair<std::string, std::string>> outputs = {{"FILE", curve_mode ? o.curve.path : o.record.path}};
  if (!o.json_path.empty()) outputs.emplace_back("--json", o.json_path);
  if (!o.report_path.empty()) outputs.emplace_back("--report", o.report_path);
  if (!o.plot_path.empty()) outputs.emplace_back("--plot", o.plot_path);
  if (!o.html_path.empty()) outputs.emplace_back("--html", o.html_path);
  if (!CheckDistinctOutputs(outputs, &why)) return UsageFailure(why);
  if ((!o.plot_path.empty() || !o.html_path.empty()) && !FindGnuplot(&why)) return RuntimeFailure(why);
  AtomicFile json, report, png, html;
  if (!o.html_path.empty() && !html.Open(o.html_path, &why)) return RuntimeFailure(why);
  if (!o.json_path.empty() && !json.Open(o.json_path, &why)) return RuntimeFailure(why);
  if (!o.report_path.empty() && !report.Open(o.report_path, &why)) return RuntimeFailure(why);
  if (!o.plot_path.empty() && !png.Open(o.plot_path, &why)) return RuntimeFailure(why);

  if (SeveralColumns(o.record)) {
    if (curve_mode) return UsageFailure("--curve is one curve: drop --columns/--imu");
    if (!o.validate_path.empty()) return UsageFailure("--validate-on checks one gyro column: drop --columns/--imu (an accelerometer axis is diagnosed without it)");
    return DiagnoseSeveral(o, d, command_line, &json, &report, &png, &html);
  }
  Provenance p = MakeProvenance(kCommand, command_line);
  DiagnosisSummary s;
  DiagnoseUnits unit;
  if (curve_mode) {
    if (!DiagnoseCurve(d, table.curve, &s)) return RuntimeFailure(o.curve.path + ": " + s.message);
    if (!table.skipped.empty()) {
      s.notes.push_back("curve: " + std::to_string(table.skipped.size()) + " row(s) not used, e.g. " +
                        table.skipped.front());
    }
    p.Add("curve", DescribeCurve(o.curve, *o.record.rate_hz));
  } else {
    std::vector<double> rate;
    RecordInfo info;
    if (const int code = ReadRateFromFile(o.record, kCommand, &rate, &info, &why); code != kExitOk) {
      return Failure{code, why};
    }
    DiagnoseProgress progress(std::filesystem::path(o.record.path).filename().string(), !o.quiet, o.progress);
    d.progress = [&](std::string_view stage, int done, int total) { progress.Update(stage, done, total); };
    const bool diagnosed = DiagnoseRecord(d, rate, info.sample_clock, &s);
    d.progress = nullptr;
    progress.Clear();
    if (!diagnosed) return RuntimeFailure(o.record.path + ": " + s.message);
    // Warned about by the reader too (avar_command.cc); the report keeps it beside the verdict.
    if (const auto stuck = DescribeConstantStretch(info.longest_constant_stretch, info.samples, info.sample_clock.rate_hz())) {
      s.notes.push_back("record: " + *stuck);
    }
    unit.record_unit = info.units;
    p.Add("input", info.path);
    p.Add("column", info.column);
    p.Add("units", info.units + " (" + info.units_source + ")");
    p.Add("sample_rate", ShortestDecimal(info.sample_clock.rate_hz()) + " Hz (" + info.rate_source + ")");
    p.Add("samples", std::to_string(rate.size()));
    if (info.dropped_nonfinite > 0) p.Add("dropped_nonfinite", std::to_string(info.dropped_nonfinite));
  }
  AddDiagnosisSettings(o, &p);

  Json validation;
  if (!o.validate_path.empty()) {
    RecordCurveOptions v = o.record;
    v.path = o.validate_path;
    std::vector<double> rate2;
    RecordInfo info2;
    if (const int code = ReadRateFromFile(v, kCommand, &rate2, &info2, &why); code != kExitOk) return Failure{code, why};
    ValidationScores scores;
    if (!ScoreOnSecondRecord(d, s, rate2, info2.sample_clock, &scores, &why)) {
      return RuntimeFailure(o.validate_path + ": " + why);
    }
    validation = ValidationJson(o.validate_path, scores);
    p.Add("validate_on", o.validate_path);
  }

  WriteText(std::cout, s, false, unit);
  if (!validation.is_null()) WriteValidation(std::cout, validation, false);
  std::cout.flush();
  if (json.is_open()) json.stream() << DiagnosisJson(s, p, validation, unit).dump(2) << "\n";
  if (report.is_open()) {
    WriteText(report.stream(), s, true, unit);
    if (!validation.is_null()) WriteValidation(report.stream(), validation, true);
    report.stream() << "\n## provenance\n\n";
    for (const auto& [k, v] : p.fields) report.stream() << "- " << k << ": " << v << "\n";
    report.stream() << "- command: `" << p.command_line << "`\n- git: " << p.git_sha << "\n";
  }
  // The file's name (a folder path, often a temporary one, says nothing to the reader of a plot),
  // and the column read from it.
  const std::string title =
      "allanlab diagnose: " + std::filesystem::path(curve_mode ? o.curve.path : o.record.path).filename().string() +
      (!curve_mode && !o.record.column.empty() ? " " + o.record.column : "");
  const std::vector<AllanPlot> panels = DiagnosePanels(s, title, unit);
  if (png.is_open() && !RenderAllanPlotGrid(panels, 2, &png, &why)) return RuntimeFailure(why);
  if (html.is_open()) {
    std::string bytes;
    if (!PlotBytes(panels, &png, html.path(), &bytes, &why)) return RuntimeFailure(why);
    std::ostringstream detail;
    WriteText(detail, s, true, unit, false);
    if (!validation.is_null()) WriteValidation(detail, validation, true);
    WriteDiagnoseHtml(html.stream(), title, {{"", MakePlainSummary(s, unit), detail.str()}}, bytes, ProvenancePairs(p));
  }
  for (AtomicFile* file : {&json, &report, &png, &html}) {
    if (file->is_open() && !file->Commit(&why)) return RuntimeFailure(why);
  }
  return std::nullopt;
}

}  // namespace

Subcommand AddDiagnoseCommand(CLI::App* parent) {
  auto options = std::make_shared<DiagnoseCommandOptions>();
  CLI::App* cmd = parent->add_subcommand(
      kCommand,
      "Where a recording departs from its fitted IEEE 952 model (several views, multiplicity "
      "controlled), which unmodelled effect explains the gap, and how far it shrinks.");
  AddRecordCurveOptions(cmd, &options->record);
  // diagnose reports each quantity in its datasheet unit and the record's own (deg/h and the
  // file's unit for a gyro, mg and the file's unit for an accelerometer): the output-unit options
  // of avar and fit have nothing to set here. Hidden from the help, and refused when given.
  std::vector<std::pair<std::string, const CLI::Option*>> refused;
  for (const char* name : {"--out-units", "--accel-out-units"}) {
    CLI::Option* option = cmd->get_option(name);
    option->group("");
    refused.emplace_back(name, option);
  }
  // FILE is optional here: --curve replaces it.
  cmd->get_option("FILE")->required(false);
  cmd->add_option("--sensor", options->sensor_path,
                  "baseline: your simulation model (sensor spec as for simulate), held as given")
      ->type_name("SPEC.yaml");
  cmd->add_option("--preset", options->preset, "baseline: a shipped sensor model, held as given")->type_name("NAME");
  cmd->add_option("--float", options->float_terms,
                  "with --sensor/--preset: refit these coefficients of it (comma list of Q,N,B,K,R)")
      ->type_name("LIST");
  cmd->add_option("--model", options->model,
                  "baseline: only these IEEE terms, fitted, no band-limit (comma list of Q,N,B,K,R; default: "
                  "what allanlab fit reports, band-limit included)")
      ->type_name("LIST");
  cmd->add_option("--trials", options->trials, "simulated records per Monte Carlo envelope (default 30; 0: OAVAR view only)")->type_name("N");
  cmd->add_option("--seed", options->seed, "seed of the simulated records (default 1)")->type_name("N");
  cmd->add_option("--false-alarm", options->false_alarm, "chance that a record of the model itself is flagged (default 0.05)")->type_name("P");
  cmd->add_option("--jobs", options->jobs, "threads (0 or unset: every core; the output is the same for any N)")->type_name("N");
  auto* quiet = cmd->add_flag("--quiet", options->quiet, "no progress line on stderr (shown only when stderr is a terminal)");
  cmd->add_flag("--progress", options->progress,
                "progress on stderr (stage, steps, time so far, time left in the stage) also when it is not a terminal: "
                "one line per stage or every 5 s")
      ->excludes(quiet);
  cmd->add_option("--json", options->json_path, "write the diagnosis as JSON (stable keys)")->type_name("OUT.json");
  cmd->add_option("--report", options->report_path, "write a Markdown report")->type_name("OUT.md");
  cmd->add_option("--html", options->html_path,
                  "write the report as one self-contained HTML page, plots inline (needs gnuplot)")
      ->type_name("OUT.html");
  cmd->add_option("--plot", options->plot_path, "draw record, baseline and verdict model (PNG, gnuplot)")->type_name("OUT.png");
  cmd->add_option("--validate-on", options->validate_path, "score the verdict's model on a second recording of the same sensor")->type_name("FILE2");
  AddCurveOptions(cmd, &options->curve);
  cmd->footer("Verdict: none (no significant gap), an effect id (bandwidth, gauss_markov, random_telegraph, harmonic,\n"
              "angle_quantization, rate_quantization, exponential_drift, bias_step, outliers, resonance), a set of up\n"
              "to three (bandwidth+resonance: what each adds is listed), or unexplained. A verdict that explains most\n"
              "of the gap but not all says so and lists what remains.\n"
              "Exit status: 0 ok (any verdict), 1 bad file or unusable record, 2 usage error.");
  return {cmd, [options, refused](const std::string& command_line) {
            for (const auto& [name, option] : refused) {
              if (option->count() == 0) continue;
              return RunCommand(kCommand, "", [&]() -> std::optional<Failure> {
                return UsageFailure(name + " does not apply to diagnose: it reports gyro quantities in deg/h and "
                                    "accelerometer quantities in mg, each beside the record's own unit; drop " + name);
              });
            }
            return RunDiagnose(*options, command_line);
          }};
}

int RunDiagnose(const DiagnoseCommandOptions& options, const std::string& command_line) {
  return RunCommand(kCommand, "", [&] { return Diagnose(options, command_line); });
}

}  // namespace allanlab::app
