#include "app/reports/diagnose_summary.h"

#include <algorithm>
#include <cmath>

#include "common/number_text.h"
#include "estimators/fit/noise_coefficient.h"

namespace allanlab::app {
namespace {

using namespace allanlab::experiments;
using Json = nlohmann::ordered_json;

std::string Describe(Effect e, const DiagnoseUnits& u) {
  switch (e) {
    case Effect::kBandwidth: return "a low-pass filter in the sensor's output chain";
    case Effect::kGaussMarkov: return "a correlated bias wander (first-order Gauss-Markov)";
    case Effect::kRandomTelegraph: return "a bias jumping between two levels (random telegraph, popcorn noise)";
    case Effect::kHarmonic: return "a periodic disturbance (vibration or an electrical line)";
    case Effect::kAngleQuantization: return "quantization of the integrated " + IntegralWord(u) + " output";
    case Effect::kRateQuantization: return "quantization of the " + QuantityWord(u) + " output";
    case Effect::kExponentialDrift: return "a warm-up drift settling exponentially from the start";
    case Effect::kBiasStep: return "a bias step";
    case Effect::kOutliers: return "spikes (outliers)";
    case Effect::kResonance: return "a narrowband resonance (a lightly damped mode driven by noise)";
  }
  return "?";
}

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string Spaced(std::string s) {
  for (char& c : s) c = c == '_' ? ' ' : c;
  return s;
}

// An effect parameter (SI, unit in its name) in the report's units (app/reports/diagnose_units.h):
// rates in deg/h or accelerations in mg (and the record's unit), their integrals in deg or m/s,
// times in s, frequencies in Hz.
PlainQuantity Quantity(const std::string& si_name, double v, const DiagnoseUnits& units) {
  PlainQuantity q;
  if (EndsWith(si_name, "_rad_per_s")) {
    q.name = Spaced(si_name.substr(0, si_name.size() - 10));
    const ReportedRate r = ReportRate(units, v);
    q.value = r.value;
    q.unit = r.unit;
    q.record_value = r.record_value;
    q.record_unit = r.record_unit;
  } else if (EndsWith(si_name, "_rad")) {
    q.name = Spaced(si_name.substr(0, si_name.size() - 4));
    q.value = ReportAngle(units, v);
    q.unit = ReportAngleUnit(units);
  } else if (si_name == "rate_hz") {
    q.name = "rate";
    q.value = v;
    q.unit = "per s";
  } else if (EndsWith(si_name, "_hz")) {
    q.name = Spaced(si_name.substr(0, si_name.size() - 3));
    q.value = v;
    q.unit = "Hz";
  } else if (EndsWith(si_name, "_s")) {
    q.name = Spaced(si_name.substr(0, si_name.size() - 2));
    q.value = v;
    q.unit = "s";
  } else {
    q.name = Spaced(si_name);
    q.value = v;
  }
  return q;
}

std::string Tau(double a, double b) {
  return (a == b ? PlainNumber(a) : PlainNumber(a) + " .. " + PlainNumber(b)) + " s";
}

std::string Where(const GapRegion& r, const DiagnoseUnits& u) {
  const std::string above = r.mean_z > 0 ? "the record above the model" : "the record below the model";
  switch (r.view) {
    case View::kOavar: return "Allan variance (oavar) at tau " + Tau(r.x_min, r.x_max) + ": " + above;
    case View::kHadamard: return "Hadamard variance (hadamard) at tau " + Tau(r.x_min, r.x_max) + ": " + above;
    case View::kHalves:
      return "the two halves of the record differ (halves) at tau " + Tau(r.x_min, r.x_max) +
             (r.mean_z > 0 ? ": the first half noisier" : ": the second half noisier");
    case View::kDynamic:
      return "the Allan variance changes along the record (dynamic) at tau " + Tau(r.x_min, r.x_max);
    case View::kPsd:
      return "spectrum (psd) at " +
             (r.x_min == r.x_max ? PlainNumber(r.x_min) : PlainNumber(r.x_min) + " .. " + PlainNumber(r.x_max)) +
             " Hz: " + above;
    case View::kKurtosis:
      return std::string(r.mean_z > 0 ? "heavier tails than Gaussian noise" : "lighter tails than Gaussian noise") +
             " (kurtosis) at tau " + Tau(r.x_min, r.x_max);
    case View::kChangePoint:
      return "the " + QuantityWord(u) + (r.mean_z > 0 ? " level rises" : " level falls") + " at t = " +
             PlainNumber(r.time_s) + " s from the start (change_point, blocks of " + Tau(r.x_min, r.x_max) + ")";
    case View::kTrend:
      return "the " + QuantityWord(u) + (r.mean_z > 0 ? " settles from above" : " settles from below") +
             " from the start, time constant " + PlainNumber(r.time_s) + " s (trend, blocks of " +
             Tau(r.x_min, r.x_max) + ")";
  }
  return "?";
}

// A line that moves: its centroid and power at the first and last block, each slope's t.
std::string LineDriftText(const experiments::LineDrift& d, double line_hz) {
  const std::string blocks = std::to_string(experiments::kLineDriftBlocks) + " blocks of " + PlainNumber(d.block_s) + " s";
  // A weak line's fitted power can end at or below its floor: then the change as a share is
  // meaningless, and only its direction is said.
  const double change = 100.0 * (d.power.last / d.power.first - 1.0);
  const std::string size = d.power.first > 0.0 ? PlainNumber(std::abs(change)) + " % " : "";
  const std::string power = std::string("its power ") + (d.power.last >= d.power.first ? "rises " : "falls ") + size +
                            "from the first block to the last (t = " + PlainNumber(d.power.t) +
                            (d.PowerDrifts() ? ")" : ", within its noise)");
  if (d.FrequencyDrifts()) {
    return "the spectral line near " + PlainNumber(line_hz) + " Hz moves along the record: its centre from " +
           PlainNumber(d.frequency_hz.first) + " Hz in the first block to " + PlainNumber(d.frequency_hz.last) +
           " Hz in the last (straight line over " + blocks + ", t = " + PlainNumber(d.frequency_hz.t) + "), " + power +
           ": a resonance whose frequency drifts (a MEMS mode follows its temperature), which no candidate "
           "models (each holds its line still)";
  }
  return "the spectral line near " + PlainNumber(line_hz) + " Hz keeps its frequency but not its strength: " + power +
         " over " + blocks + ", which no candidate models (each holds its line's power constant)";
}

// The regions left, per view: its x range over all of them and the largest |z|.
std::vector<std::string> Remains(const std::vector<GapRegion>& regions) {
  std::vector<std::string> out;
  std::vector<View> seen;
  for (const GapRegion& first : regions) {
    if (std::find(seen.begin(), seen.end(), first.view) != seen.end()) continue;
    seen.push_back(first.view);
    double lo = first.x_min, hi = first.x_max, z = 0.0;
    int count = 0;
    for (const GapRegion& r : regions) {
      if (r.view != first.view) continue;
      lo = std::min(lo, r.x_min), hi = std::max(hi, r.x_max), z = std::max(z, r.max_abs_z);
      ++count;
    }
    const std::string range = first.view == View::kPsd
                                  ? (lo == hi ? PlainNumber(lo) : PlainNumber(lo) + " .. " + PlainNumber(hi)) + " Hz"
                                  : (first.view == View::kChangePoint || first.view == View::kTrend ? "blocks of " : "tau ") +
                                        Tau(lo, hi);
    out.push_back(std::string(ViewId(first.view)) + " at " + range + " (max |z| " + PlainNumber(z) +
                  (count > 1 ? ", " + std::to_string(count) + " regions" : "") + ")");
  }
  return out;
}

std::string QuantityText(const PlainQuantity& q) {
  std::string t = q.name + " " + PlainNumber(q.value) + (q.unit.empty() ? "" : " " + q.unit);
  if (q.record_value) t += " (" + PlainNumber(*q.record_value) + " " + q.record_unit + ")";
  if (!q.caveat.empty()) t += " [" + q.caveat + "]";
  return t;
}

// A correlation time near the sample period is where the fit ran out of record, not a property
// measured; a cutoff near or above the output's Nyquist frequency is a filter ahead of the
// output's decimation (allowed: an anti-alias filter above fs/2), whose cutoff the record pins only
// loosely. Values at a fit's edge are refused as candidates (experiments/diagnosis/physical_bounds.h).
void AddCaveat(SampleClock sample_clock, PlainQuantity* q) {
  if (!sample_clock.IsValid()) return;
  const double sample_period_s = sample_clock.period_s();
  const double nyquist = 0.5 * sample_clock.rate_hz();
  if (q->unit == "s" && q->name != "time" && q->value < 2.0 * sample_period_s) {
    q->caveat = "within 2x of the " + PlainNumber(sample_period_s) + " s sample period: the record cannot resolve it";
  } else if (q->name == "cutoff" && q->value > 0.9 * nyquist) {
    q->caveat = std::string(q->value > nyquist ? "above" : "near") + " the output's " + PlainNumber(nyquist) +
                " Hz Nyquist frequency: a filter ahead of the output's decimation, its cutoff loosely determined";
  }
}

std::string EffectText(const PlainEffect& e) {
  return e.description + " [" + e.id + "]" + (e.quantities.empty() ? "" : ": " + QuantitiesText(e));
}

std::string ShrinkText(const PlainShrink& v) {
  const double factor = v.chi2_after > 0.0 ? v.chi2_before / v.chi2_after : 0.0;
  return v.view + " " + PlainNumber(v.chi2_before) + " -> " + PlainNumber(v.chi2_after) +
         (factor > 0.0 ? " (" + PlainNumber(factor) + "x)" : "");
}

Json CoefficientJson(bool fitted, double value, double sigma, double upper) {
  if (fitted) return Json{{"value", value}, {"sigma", sigma}};
  return upper > 0.0 ? Json{{"upper_limit", upper}} : Json(nullptr);
}

double UpperLimit(const DiagnoseUnits& units, estimators::Coefficient k, const estimators::CoefficientEstimate& e) {
  return !e.fitted && e.has_upper_limit ? CoefficientValue(units, k, e.upper_limit_si) : 0.0;
}

}  // namespace

std::string PlainNumber(double v) { return SignificantDigits(v, 4); }

std::string QuantitiesText(const PlainEffect& e) {
  std::string t;
  for (std::size_t i = 0; i < e.quantities.size(); ++i) t += (i ? ", " : "") + QuantityText(e.quantities[i]);
  return t;
}

PlainEffect MakePlainEffect(const EffectInstance& e, const DiagnoseUnits& units, SampleClock sample_clock) {
  PlainEffect pe{std::string(EffectId(e.effect)), Describe(e.effect, units), {}};
  if (const std::string variant = EffectVariant(e); !variant.empty()) pe.description += " (" + variant + ")";
  for (const std::string& name : EffectParameterNames(e.effect)) {
    pe.quantities.push_back(Quantity(name, e.params.at(name), units));
    AddCaveat(sample_clock, &pe.quantities.back());
  }
  return pe;
}

Json PlainEffectJson(const PlainEffect& e) {
  Json q = Json::array();
  for (const PlainQuantity& x : e.quantities) {
    Json one{{"name", x.name}, {"value", x.value}, {"unit", x.unit}};
    if (x.record_value) one["record_value"] = *x.record_value, one["record_unit"] = x.record_unit;
    if (!x.caveat.empty()) one["caveat"] = x.caveat;
    q.push_back(one);
  }
  return {{"id", e.id}, {"description", e.description}, {"quantities", q}};
}

PlainSummary MakePlainSummary(const DiagnosisSummary& s, const DiagnoseUnits& units) {
  PlainSummary p;
  p.verdict = s.verdict;
  p.threshold_z = s.threshold;
  p.points = s.total_points;
  for (const GapRegion& r : s.regions) p.where.push_back(Where(r, units));
  const CandidateResult* c = s.verdict_candidate >= 0 ? &s.candidates[s.verdict_candidate] : nullptr;
  p.named = c != nullptr && s.verdict != "unexplained";
  p.best_tried = c != nullptr && s.verdict == "unexplained";
  if (c != nullptr) {
    p.model_label = "with " + c->id();
    for (const EffectInstance& e : c->effects) p.effects.push_back(MakePlainEffect(e, units, s.sample_clock));
    std::vector<View> departing;
    for (const GapRegion& r : s.regions) {
      if (std::find(departing.begin(), departing.end(), r.view) == departing.end()) departing.push_back(r.view);
    }
    for (View v : departing) {
      const GapMetrics before = s.before.View(v), after = c->after.View(v);
      if (after.points == 0) continue;  // not assessed for this candidate
      p.shrink.push_back({std::string(ViewId(v)), before.points, before.chi2, after.chi2});
    }
    if (c->after.has_heldout) {
      p.shrink.push_back({"held-out", c->after.heldout.points, c->heldout_before.chi2, c->after.heldout.chi2});
    }
    if (p.best_tried) p.best_tried_why = c->why_not_verdict;
    p.remains = Remains(s.remaining);
  }
  if (s.line_drift && (s.line_drift->FrequencyDrifts() || s.line_drift->PowerDrifts())) {
    p.line_drift = LineDriftText(*s.line_drift, s.line_drift_frequency_hz);
  }
  for (std::size_t i = 0; i < s.candidates.size(); ++i) {
    const CandidateResult& other = s.candidates[i];
    if (static_cast<int>(i) == s.verdict_candidate || !other.closes_gap) continue;
    p.also_closes.emplace_back(other.id(), other.why_not_verdict);
  }
  if (s.baseline_model.band_limit.enabled()) {
    const auto& b = s.baseline_model.band_limit;
    const double nyquist = s.sample_clock.period_s() > 0.0 ? 0.5 / s.sample_clock.period_s() : 0.0;
    const bool given = s.baseline_source == experiments::DiagnoseOptions::Baseline::kSensor;
    p.baseline_note = std::string("the baseline includes ") +
                      (given ? "your sensor model's band-limit: a "
                             : "the output chain's band-limit that allanlab fit finds: a ") +
                      (b.kind == sim::LowPassKind::kFirstOrder ? "first-order" : "second-order Butterworth") +
                      " low-pass at " + PlainNumber(b.cutoff_hz) + " Hz" +
                      (b.sampling == sim::OutputSampling::kAverage ? ", averaged to the output rate" : "") + " (held)";
    // A fitted cutoff near Nyquist is loosely determined and could read as a finding; the user's
    // own filter is not one to dismiss.
    if (!given && nyquist > 0.0 && b.cutoff_hz > 0.9 * nyquist) {
      p.baseline_note += "; a cutoff at or above the " + PlainNumber(nyquist) +
                         " Hz Nyquist frequency shapes only the shortest taus, not a finding";
    }
  }
  for (estimators::Coefficient k : estimators::kAllCoefficients) {
    const auto& b = s.baseline.at(k);
    if (!b.asked || (!b.fitted && !b.has_upper_limit && (c == nullptr || !c->fit.at(k).fitted))) continue;  // in neither model
    PlainCoefficient pc;
    pc.id = std::string(estimators::CoefficientId(k));
    pc.unit = CoefficientUnit(units, k);
    pc.baseline_fitted = b.fitted;
    pc.baseline = CoefficientValue(units, k, b.value_si);
    pc.baseline_sigma = CoefficientValue(units, k, b.sigma_si);
    pc.baseline_upper = UpperLimit(units, k, b);
    if (c != nullptr) {
      const auto& m = c->fit.at(k);
      pc.model_fitted = m.fitted;
      pc.model = CoefficientValue(units, k, m.value_si);
      pc.model_sigma = CoefficientValue(units, k, m.sigma_si);
      pc.model_upper = UpperLimit(units, k, m);
    }
    p.coefficients.push_back(pc);
  }
  return p;
}

std::vector<std::string> PlainLines(const PlainSummary& p) {
  std::vector<std::string> lines;
  if (p.where.empty()) {
    lines.push_back("the record agrees with the baseline model in every view (no point beyond |z| = " +
                    PlainNumber(p.threshold_z) + " of " + std::to_string(p.points) + ")");
  } else {
    for (const std::string& w : p.where) lines.push_back("departs: " + w);
  }
  for (std::size_t i = 0; i < p.effects.size(); ++i) {
    const std::string lead = i > 0 ? "together with " : (p.named ? "explained by " : "not explained; the best tried: ");
    lines.push_back(lead + EffectText(p.effects[i]));
  }
  if (!p.best_tried_why.empty()) lines.push_back("not named: it " + p.best_tried_why);
  if (!p.remains.empty()) {
    std::string t = "still departs " + p.model_label + ": ";
    for (std::size_t i = 0; i < p.remains.size(); ++i) t += (i ? "; " : "") + p.remains[i];
    lines.push_back(t);
  }
  for (const auto& [id, why] : p.also_closes) {
    lines.push_back("not the verdict: " + id + (why.empty() ? "" : " " + why));
  }
  if (!p.line_drift.empty()) lines.push_back(p.line_drift);
  if (!p.baseline_note.empty()) lines.push_back(p.baseline_note);
  if (!p.shrink.empty()) {
    std::string t = "gap chi2 before -> after " + p.model_label + ": ";
    for (std::size_t i = 0; i < p.shrink.size(); ++i) t += (i ? ", " : "") + ShrinkText(p.shrink[i]);
    lines.push_back(t);
  }
  return lines;
}

void WritePlainText(std::ostream& os, const PlainSummary& p) {
  os << "in plain words:\n";
  for (const std::string& line : PlainLines(p)) os << "  " << line << "\n";
  if (p.coefficients.empty()) {
    os << "  coefficients: none fitted (the sensor model's, held as given)\n";
    return;
  }
  os << "  coefficients (baseline" << (p.model_label.empty() ? "" : " -> " + p.model_label) << "):\n";
  for (const PlainCoefficient& c : p.coefficients) {
    // The unit beside the name: a value that is "not fitted" has none to end on.
    os << "    " << c.id << " [" << c.unit << "] "
       << CoefficientText(c.baseline_fitted, c.baseline, c.baseline_sigma, c.baseline_upper);
    if (!p.model_label.empty()) os << " -> " << CoefficientText(c.model_fitted, c.model, c.model_sigma, c.model_upper);
    os << "\n";
  }
}

void WritePlainMarkdown(std::ostream& os, const PlainSummary& p) {
  os << "## In plain words\n\n";
  for (const std::string& line : PlainLines(p)) os << "- " << line << "\n";
  if (p.coefficients.empty()) {
    os << "- coefficients: none fitted (the sensor model's, held as given)\n\n";
    return;
  }
  os << "\n| coefficient | unit | baseline |" << (p.model_label.empty() ? "" : " " + p.model_label + " |")
     << "\n|---|---|---|" << (p.model_label.empty() ? "" : "---|") << "\n";
  for (const PlainCoefficient& c : p.coefficients) {
    os << "| " << c.id << " | " << c.unit << " | " << CoefficientText(c.baseline_fitted, c.baseline, c.baseline_sigma, c.baseline_upper)
       << " |";
    if (!p.model_label.empty()) os << " " << CoefficientText(c.model_fitted, c.model, c.model_sigma, c.model_upper) << " |";
    os << "\n";
  }
  os << "\n";
}

Json PlainJson(const PlainSummary& p) {
  Json j;
  j["lines"] = PlainLines(p);
  j["where"] = p.where;
  Json effects = Json::array();
  for (const PlainEffect& e : p.effects) effects.push_back(PlainEffectJson(e));
  j["effects"] = effects;
  j["effects_are"] = p.named ? "verdict" : (p.best_tried ? "best_tried" : "none");
  if (p.best_tried) j["best_tried_not_named_because"] = p.best_tried_why;
  Json closes = Json::array();
  for (const auto& [id, why] : p.also_closes) closes.push_back({{"effect", id}, {"not_the_verdict_because", why}});
  j["also_closes"] = closes;
  Json shrink = Json::array();
  for (const PlainShrink& v : p.shrink) {
    shrink.push_back({{"view", v.view}, {"points", v.points}, {"chi2_before", v.chi2_before}, {"chi2_after", v.chi2_after}});
  }
  j["shrink"] = shrink;
  j["remains"] = p.remains;
  if (!p.line_drift.empty()) j["line_drift"] = p.line_drift;
  Json coefficients = Json::array();
  for (const PlainCoefficient& c : p.coefficients) {
    Json one{{"id", c.id}, {"unit", c.unit},
             {"baseline", CoefficientJson(c.baseline_fitted, c.baseline, c.baseline_sigma, c.baseline_upper)}};
    if (!p.model_label.empty()) one["model"] = CoefficientJson(c.model_fitted, c.model, c.model_sigma, c.model_upper);
    coefficients.push_back(one);
  }
  j["coefficients"] = coefficients;
  j["model"] = p.model_label;
  return j;
}

std::string CoefficientText(bool fitted, double value, double sigma, double upper) {
  if (fitted) return PlainNumber(value) + " +- " + PlainNumber(sigma);
  return upper > 0.0 ? "< " + PlainNumber(upper) + " (95 % upper limit)" : "not fitted";
}

}  // namespace allanlab::app
