#include "app/input/curve_options.h"

#include <cmath>

#include "app/reports/provenance.h"
#include "app/failure.h"
#include "common/number_text.h"

namespace allanlab::app {

void AddCurveOptions(CLI::App* cmd, CurveCommandOptions* options) {
  cmd->add_option("--curve", options->path,
                  "curve mode: a published Allan curve (a header naming tau_s or tau and "
                  "--curve-column; '-' for standard input) instead of FILE; needs "
                  "--record-length and --rate")
      ->type_name("CSV");
  cmd->add_option("--curve-column", options->column,
                  "column of --curve (default adev_x); a name starting with avar or var holds "
                  "variances, any other deviations")
      ->type_name("NAME");
  cmd->add_option("--curve-units", options->units,
                  "rate unit of the --curve column: deg/h (default), deg/s or rad/s (squared for "
                  "variances)")
      ->type_name("UNIT");
  cmd->add_option("--record-length", options->record_length_s,
                  "curve mode: length of the record the curve came from [s]")
      ->type_name("S");
}

int ReadCurveFromOptions(const CurveCommandOptions& o, std::optional<double> rate_hz,
                         CurveTable* table, std::string* error) {
  const auto positive = [](const std::optional<double>& v) { return v && std::isfinite(*v) && *v > 0.0; };
  if (!positive(o.record_length_s) || !positive(rate_hz)) {
    *error = "--curve needs --record-length S > 0 and --rate HZ > 0 (the record the curve came from)";
    return kExitUsageError;
  }
  CurveTableOptions read{o.path, o.column, RateUnit::kDegPerHour, *o.record_length_s, *rate_hz};
  std::string why;
  if (!ParseRateUnit(o.units, &read.unit, &why)) {
    *error = "--curve-units: " + why;
    return kExitUsageError;
  }
  CurveTableError e;
  if (!ReadCurveTable(read, table, &e)) {
    *error = e.message;
    return e.exit_code;
  }
  return kExitOk;
}

AvarReport ReportOfCurve(const CurveCommandOptions& o, const CurveTable& table) {
  AvarReport r;
  const estimators::AvarCurve& c = table.curve;
  r.record.path = o.path == "-" ? "stdin" : o.path;
  r.record.column = o.column;
  r.record.sample_clock = c.sample_clock;
  r.record.rate_source = "--rate (curve mode)";
  r.record.units = o.units + (table.variance ? " (squared)" : "");
  r.record.units_source = "--curve-units";
  r.record.samples = c.num_samples;
  r.input_units = r.record.units;
  r.summary.ok = true;
  r.summary.num_samples = c.num_samples;
  r.summary.options.statistic = estimators::Statistic::kAllanOverlapping;
  r.summary.options.sample_clock = c.sample_clock;
  r.summary.options.confidence_method = estimators::ConfidenceMethod::kNone;
  for (std::size_t k = 0; k < c.size(); ++k) {
    estimators::AvarPoint p;
    p.m = c.m[k];
    p.tau_s = c.tau_s[k];
    p.value = c.avar[k];
    p.terms = c.num_samples - 2 * c.m[k] + 1;
    p.edf = c.edf[k];
    r.summary.points.push_back(p);
  }
  return r;
}

std::string DescribeCurve(const CurveCommandOptions& o, double rate_hz) {
  return o.path + " column " + o.column + " (" + o.units + "), record " +
         ShortestDecimal(o.record_length_s.value_or(0.0)) + " s at " + ShortestDecimal(rate_hz) +
         " Hz";
}

}  // namespace allanlab::app
