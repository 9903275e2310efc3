#pragma once
// The first lines of a `diagnose` report, in plain words and in one set of units: where the
// record departs from the baseline (tau range; for a step or a warm-up drift, the time in the
// record), which effect explains it in sensor terms (app/reports/diagnose_units.h: a gyro's rates in deg/h, an
// accelerometer's accelerations in mg, each also in the record's unit),
// how far the gap shrinks with it, view by view, and the baseline's and the verdict model's
// coefficients side by side. Stdout, the Markdown report, the JSON (`summary`) and the HTML
// report all print this one structure, so they say the same thing in the same units.
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/reports/diagnose_units.h"
#include "experiments/diagnosis/diagnose.h"

namespace allanlab::app {

struct PlainQuantity {
  std::string name;  // "size", "time", "cutoff", ...
  double value = 0.0;
  std::string unit;  // "deg/h", "mg", "s", "Hz", "" (a pure number)
  // The same rate in the record's unit when it is not the report's (nullopt otherwise).
  std::optional<double> record_value;
  std::string record_unit;
  // Said beside the value when a fit sits at the record's resolution (a correlation time within
  // a factor 2 of the sample period, a cutoff within 10 % of the Nyquist frequency).
  std::string caveat;
};

struct PlainEffect {
  std::string id;           // "bias_step"
  std::string description;  // "a bias step"
  std::vector<PlainQuantity> quantities;
};

struct PlainShrink {
  std::string view;  // "oavar", ..., or "held-out"
  int points = 0;
  double chi2_before = 0.0, chi2_after = 0.0;
};

struct PlainCoefficient {
  std::string id, unit;  // "N", "deg/sqrt(h)"
  bool baseline_fitted = false, model_fitted = false;
  double baseline = 0.0, baseline_sigma = 0.0, model = 0.0, model_sigma = 0.0;
  // Not fitted (left out by the term choice, or at zero): the one-sided 95 % upper limit, as
  // `allanlab fit` reports it; 0 when there is none.
  double baseline_upper = 0.0, model_upper = 0.0;
};

struct PlainSummary {
  std::string verdict;              // as DiagnosisSummary::verdict
  bool named = false;               // an effect (or set) explains the gap
  bool best_tried = false;          // "unexplained": the effects are the best tried
  std::vector<std::string> where;   // one phrase per gap region
  std::vector<PlainEffect> effects;
  std::vector<PlainShrink> shrink;  // the views that depart, then held-out (named or best tried)
  std::vector<PlainCoefficient> coefficients;
  // What still departs with the verdict's (or best tried) model, one phrase per view.
  std::vector<std::string> remains;
  // Unexplained: why the best tried was not named (CandidateResult::why_not_verdict).
  std::string best_tried_why;
  // The other candidates that close the gap in the views they were scored on, and why each is
  // not the verdict (so the verdict line and the candidates' table agree).
  std::vector<std::pair<std::string, std::string>> also_closes;
  std::string model_label;          // "with bias_step" (empty: baseline only)
  std::string baseline_note;        // the baseline's band-limit, when it has one
  // A spectral line that moves along the record (frequency or power), when one does.
  std::string line_drift;
  double threshold_z = 0.0;
  int points = 0;
};

// One effect's parameters in the report's units, with their caveats (as `effects` holds them).
PlainEffect MakePlainEffect(const experiments::EffectInstance& e, const DiagnoseUnits& units, SampleClock sample_clock);
// {"id", "description", "quantities": [{"name", "value", "unit", "record_value", "record_unit",
// "caveat"}]}: an effect as JSON `summary.effects` and each candidate's `params_reported` give it.
nlohmann::ordered_json PlainEffectJson(const PlainEffect& e);

// `units`: the column's sensor and the unit it was read in (app/reports/diagnose_units.h).
PlainSummary MakePlainSummary(const experiments::DiagnosisSummary& s, const DiagnoseUnits& units);

// The sentences (one per line, no markup): what stdout prints first and the Markdown lists.
std::vector<std::string> PlainLines(const PlainSummary& p);
// Stdout: "in plain words:" and the lines indented, then the coefficient pairs.
void WritePlainText(std::ostream& os, const PlainSummary& p);
// Markdown: a "## In plain words" list and the coefficients side by side as a table.
void WritePlainMarkdown(std::ostream& os, const PlainSummary& p);
// JSON `summary`: the same numbers, keyed (value, unit).
nlohmann::ordered_json PlainJson(const PlainSummary& p);
// Significant digits every form prints (4; the consistency test parses at this precision).
std::string PlainNumber(double v);
// One coefficient as every form prints it: "2.435 +- 0.002833", "< 119.3 (95 % upper limit)"
// (not fitted, with its limit) or "not fitted".
std::string CoefficientText(bool fitted, double value, double sigma, double upper);
// An effect's parameters in the report's units: "size 15 deg/h (0.004167 deg/s), time 2500 s".
std::string QuantitiesText(const PlainEffect& e);

}  // namespace allanlab::app
