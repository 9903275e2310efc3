#include "app/reports/avar_report.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "common/number_text.h"
#include "estimators/estimate_distribution.h"
#include "sim/units.h"

namespace allanlab::app {
namespace {

using estimators::Statistic;


// 0.683 -> "68.3 %" (0.683 * 100 is 68.30000000000001 in binary).
std::string Percent(double fraction) { return SignificantDigits(fraction * 100, 6) + " %"; }

std::string Identifier(const std::string& unit) {
  std::string out;
  for (char c : unit) out += c == '/' ? std::string("_per_") : std::string(1, c);
  return out;
}

std::string StatisticDescription(Statistic s) {
  switch (s) {
    case Statistic::kAllanNonOverlapping:
      return "non-overlapping Allan variance (IEEE 952 Annex C)";
    case Statistic::kAllanOverlapping:
      return "overlapping Allan variance";
    case Statistic::kModifiedAllan:
      return "modified Allan variance";
    case Statistic::kHadamardNonOverlapping:
      return "non-overlapping Hadamard variance";
    case Statistic::kHadamardOverlapping:
      return "overlapping Hadamard variance";
    case Statistic::kTotal:
      return "total variance (NIST SP 1065)";
    case Statistic::kTime:
      return "time variance (tau^2 MVAR / 3)";
  }
  return "?";
}

std::string IntervalDescription(const AvarReport& r) {
  const estimators::AvarOptions& o = r.summary.options;
  const std::string level = Percent(o.confidence);
  // Where the cap applies at all (a tau with more m-averages than it): say so.
  const std::string from =
      o.identification_max_averages > 0 && r.summary.num_samples > o.identification_max_averages
          ? " (from at most " + std::to_string(o.identification_max_averages) +
                " m-averages, the middle of the record)"
          : "";
  switch (o.confidence_method) {
    case estimators::ConfidenceMethod::kNone:
      return "none";
    case estimators::ConfidenceMethod::kSimple:
      return "chi-square " + level + " with EDF = clusters - 1 (IEEE 952 simple error)";
    case estimators::ConfidenceMethod::kGreenhallRiley:
      return "chi-square " + level + " with the Greenhall-Riley EDF, alpha identified per tau" + from;
    case estimators::ConfidenceMethod::kAuto:
      return "chi-square " + level +
             " with the EDF measured on the record at short taus (edf marked r) and the "
             "Greenhall-Riley EDF at the identified alpha elsewhere; at <= " +
             std::to_string(estimators::kDistributionIntervalMaxClusters) +
             " clusters the estimate's own distribution at that alpha (edf marked d)" + from;
  }
  return "?";
}

std::string TypeName(estimators::InputKind kind) {
  return kind == estimators::InputKind::kAngle ? "angle" : "rate";
}

std::string RecordLine(const AvarReport& r) {
  const RecordInfo& i = r.record;
  return i.path + ", " + i.column + ", " + std::to_string(r.summary.num_samples) + " " +
         (r.sensor == ImuSensor::kAccelerometer ? std::string("accelerometer")
                                                 : TypeName(r.summary.options.input)) +
         " samples at " + ShortestDecimal(i.sample_clock.rate_hz()) + " Hz (" +
         i.rate_source + "), input in " + r.input_units + " (" + i.units_source + ")";
}

std::vector<std::string> Notes(const AvarReport& r) {
  std::vector<std::string> notes;
  if (r.record.dropped_nonfinite > 0) {
    notes.push_back(std::to_string(r.record.dropped_nonfinite) +
                    " non-finite value(s) dropped (--drop-nonfinite)");
  }
  if (r.record.time.irregular_steps > 0) {
    notes.push_back(TimeSteps::Describe(r.record.time, r.record.time_column) +
                    ": the estimator assumes uniform sampling");
  }
  if (r.streamed) {
    std::int64_t first_strided = 0;
    for (std::size_t k = 0; k < r.overlap_stride.size(); ++k) {
      if (r.overlap_stride[k] > 1 && first_strided == 0) first_strided = r.summary.points[k].m;
    }
    if (first_strided > 0 && r.summary.options.statistic == Statistic::kAllanOverlapping) {
      notes.push_back("--stream: from m = " + std::to_string(first_strided) +
                      " on, overlapping windows start every m/" +
                      std::to_string(r.stream_exact_max_m) + " samples (see the stride column)");
    }
  }
  return notes;
}

}  // namespace

std::string VarianceName(Statistic s) {
  switch (s) {
    case Statistic::kAllanNonOverlapping:
    case Statistic::kAllanOverlapping:
      return "AVAR";
    case Statistic::kModifiedAllan:
      return "MVAR";
    case Statistic::kHadamardNonOverlapping:
    case Statistic::kHadamardOverlapping:
      return "HVAR";
    case Statistic::kTotal:
      return "TOTVAR";
    case Statistic::kTime:
      return "TVAR";
  }
  return "VAR";
}

std::string DeviationName(Statistic s) {
  std::string name = VarianceName(s);
  return name.substr(0, name.size() - 3) + "DEV";
}

double DeviationFactor(const AvarReport& r) {
  const bool time = r.summary.options.statistic == Statistic::kTime;
  if (r.sensor == ImuSensor::kAccelerometer) return time ? 1.0 : AccelFromSi(r.accel_output_unit, 1.0);
  if (time) return r.output_unit == RateUnit::kRadPerSecond ? 1.0 : 1.0 / units::kRadPerDeg;
  return FromRadPerSecond(r.output_unit, 1.0);
}

std::string DeviationUnit(const AvarReport& r) {
  if (r.sensor == ImuSensor::kAccelerometer) {
    return r.summary.options.statistic == Statistic::kTime ? "m/s" : std::string(AccelUnitName(r.accel_output_unit));
  }
  if (r.summary.options.statistic == Statistic::kTime) {
    return r.output_unit == RateUnit::kRadPerSecond ? "rad" : "deg";
  }
  return std::string(RateUnitName(r.output_unit));
}

std::vector<AvarRow> AvarRows(const AvarReport& r) {
  const double f = DeviationFactor(r);
  const bool interval = r.summary.options.confidence_method != estimators::ConfidenceMethod::kNone;
  std::vector<AvarRow> rows;
  for (const estimators::AvarPoint& p : r.summary.points) {
    AvarRow row;
    row.m = p.m;
    row.tau_s = p.tau_s;
    row.var = p.value * f * f;
    row.dev = std::sqrt(std::max(row.var, 0.0));
    row.terms = p.terms;
    row.edf = p.edf;
    row.has_interval = interval && p.edf > 0;
    if (row.has_interval) {
      row.dev_low = std::sqrt(std::max(p.ci_low, 0.0)) * f;
      row.dev_high = std::sqrt(std::max(p.ci_high, 0.0)) * f;
    }
    row.alpha = p.alpha;
    row.alpha_identified = p.alpha_identified;
    row.edf_from_record = p.edf_from_record;
    row.ci_from_distribution = p.ci_from_distribution;
    rows.push_back(row);
  }
  return rows;
}

void WriteAvarTable(std::ostream& os, const AvarReport& r) {
  const Statistic s = r.summary.options.statistic;
  const std::string unit = DeviationUnit(r);
  const bool show_stride = r.streamed && s == Statistic::kAllanOverlapping;
  os << "# allanlab avar: " << RecordLine(r) << "\n";
  os << "# " << StatisticDescription(s) << ", taus " << r.taus_text << ", interval "
     << IntervalDescription(r) << "\n";
  char line[256];
  std::snprintf(line, sizeof line, "%12s %14s %12s %10s %10s %12s %12s %6s%s\n", "tau[s]",
                (VarianceName(s) + "[(" + unit + ")^2]").c_str(),
                (DeviationName(s) + "[" + unit + "]").c_str(), "terms", "EDF",
                (DeviationName(s) + "_low").c_str(), (DeviationName(s) + "_high").c_str(), "alpha",
                show_stride ? "  stride" : "");
  os << line;
  bool any_unidentified = false;
  const std::vector<AvarRow> rows = AvarRows(r);
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const AvarRow& row = rows[k];
    char low[32] = "-", high[32] = "-", edf[32] = "-", alpha[16] = "-";
    if (row.has_interval) {
      std::snprintf(low, sizeof low, "%.6g", row.dev_low);
      std::snprintf(high, sizeof high, "%.6g", row.dev_high);
      std::snprintf(edf, sizeof edf, "%.4g%s", row.edf,
                    row.edf_from_record ? "r" : (row.ci_from_distribution ? "d" : ""));
      // alpha only matters for (and is only identified by) the Greenhall-Riley EDF and the
      // estimate's distribution.
      const estimators::ConfidenceMethod method = r.summary.options.confidence_method;
      if (method == estimators::ConfidenceMethod::kGreenhallRiley ||
          (method == estimators::ConfidenceMethod::kAuto && !row.edf_from_record)) {
        std::snprintf(alpha, sizeof alpha, "%d%s", row.alpha, row.alpha_identified ? "" : "*");
        any_unidentified |= !row.alpha_identified;
      }
    }
    char stride[32] = "";
    if (show_stride)
      std::snprintf(stride, sizeof stride, "  %6lld", static_cast<long long>(r.overlap_stride[k]));
    std::snprintf(line, sizeof line, "%12.6g %14.6g %12.6g %10lld %10s %12s %12s %6s%s\n",
                  row.tau_s, row.var, row.dev, static_cast<long long>(row.terms), edf, low, high,
                  alpha, stride);
    os << line;
  }
  if (any_unidentified) {
    os << "# alpha*: fixed, held from a shorter tau, or not identifiable at that tau (not measured "
          "there)\n";
  }
  for (const estimators::DroppedTau& d : r.summary.dropped) {
    os << "# dropped: tau " << ShortestDecimal(d.tau_s) << " s (m = " << d.m << "): " << d.reason << "\n";
  }
  for (const std::string& note : Notes(r)) os << "# note: " << note << "\n";
}

void WriteAvarCsv(std::ostream& os, const AvarReport& r) {
  const Statistic s = r.summary.options.statistic;
  const std::string unit = Identifier(DeviationUnit(r));
  const std::string var = VarianceName(s), dev = DeviationName(s);
  Provenance p = r.provenance;
  for (const std::string& note : Notes(r)) p.Add("note", note);
  os << ProvenanceCommentLines(p);
  std::string lower_var = var, lower_dev = dev;
  for (char& c : lower_var) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (char& c : lower_dev) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  os << "m,tau_s," << lower_var << "_" << unit << "_sq," << lower_dev << "_" << unit
     << ",terms,edf," << lower_dev << "_low_" << unit << "," << lower_dev << "_high_" << unit
     << ",alpha,alpha_identified" << (r.streamed ? ",overlap_stride" : "") << "\n";
  const std::vector<AvarRow> rows = AvarRows(r);
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const AvarRow& row = rows[k];
    os << row.m << "," << ShortestDecimal(row.tau_s) << "," << ShortestDecimal(row.var) << "," << ShortestDecimal(row.dev)
       << "," << row.terms << "," << ShortestDecimal(row.edf) << ","
       << (row.has_interval ? ShortestDecimal(row.dev_low) : "") << ","
       << (row.has_interval ? ShortestDecimal(row.dev_high) : "") << "," << row.alpha << ","
       << (row.alpha_identified ? 1 : 0);
    if (r.streamed) os << "," << r.overlap_stride[k];
    os << "\n";
  }
}

nlohmann::ordered_json AvarJson(const AvarReport& r) {
  const RecordInfo& i = r.record;
  const Statistic s = r.summary.options.statistic;
  nlohmann::ordered_json j;
  j["provenance"] = ProvenanceJson(r.provenance);
  nlohmann::ordered_json input;
  input["path"] = i.path;
  input["format"] = RecordFormatName(i.format);
  input["compression"] = CompressionName(i.compression);
  input["column"] = i.column;
  input["time_column"] = i.time_column;
  input["type"] = TypeName(r.summary.options.input);
  input["sensor"] = ImuSensorName(r.sensor);
  input["units"] = r.input_units;
  input["units_source"] = i.units_source;
  input["samples_read"] = i.samples;
  input["rate_samples"] = r.summary.num_samples;
  input["dropped_nonfinite"] = i.dropped_nonfinite;
  input["sample_rate_hz"] = i.sample_clock.rate_hz();
  input["sample_rate_source"] = i.rate_source;
  if (!i.time_column.empty()) {
    // Positions are lines of a text file, or message numbers of a ROS bag: the keys say which.
    const std::string& at = i.time.position;
    input["time_steps"] = {{"nominal_s", i.time.nominal_step_s},
                           {"irregular", i.time.irregular_steps},
                           {"largest_s", i.time.largest_step_s},
                           {"largest_" + at, i.time.largest_step_line},
                           {"smallest_s", i.time.smallest_step_s},
                           {"smallest_" + at, i.time.smallest_step_line}};
  }
  j["input"] = input;
  const estimators::AvarOptions& o = r.summary.options;
  j["estimator"] = {
      {"statistic", estimators::StatisticId(s)},
      {"taus", r.taus_text},
      {"interval", IntervalDescription(r)},
      {"confidence", o.confidence},
      {"streamed", r.streamed},
  };
  if (r.streamed) j["estimator"]["stream_exact_max_m"] = r.stream_exact_max_m;
  const std::string unit = DeviationUnit(r);
  j["units"] = {{"tau", "s"},
                {"var", "(" + unit + ")^2"},
                {"dev", unit},
                {"var_name", VarianceName(s)},
                {"dev_name", DeviationName(s)}};
  nlohmann::ordered_json points = nlohmann::ordered_json::array();
  const std::vector<AvarRow> rows = AvarRows(r);
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const AvarRow& row = rows[k];
    nlohmann::ordered_json p = {{"m", row.m},         {"tau_s", row.tau_s},
                                {"var", row.var},     {"dev", row.dev},
                                {"terms", row.terms}, {"edf", row.edf},
                                {"alpha", row.alpha}, {"alpha_identified", row.alpha_identified}};
    if (row.has_interval) {
      p["dev_low"] = row.dev_low;
      p["dev_high"] = row.dev_high;
    } else {
      p["dev_low"] = nullptr;
      p["dev_high"] = nullptr;
    }
    p["edf_from_record"] = row.edf_from_record;
    p["ci_from_distribution"] = row.ci_from_distribution;
    if (r.streamed) p["overlap_stride"] = r.overlap_stride[k];
    points.push_back(p);
  }
  j["points"] = points;
  nlohmann::ordered_json dropped = nlohmann::ordered_json::array();
  for (const estimators::DroppedTau& d : r.summary.dropped) {
    dropped.push_back({{"tau_s", d.tau_s}, {"m", d.m}, {"reason", d.reason}});
  }
  j["dropped"] = dropped;
  j["notes"] = Notes(r);
  j["message"] = r.summary.message;
  return j;
}

AllanPlot AvarPlot(const AvarReport& r) {
  const Statistic s = r.summary.options.statistic;
  const std::string unit = DeviationUnit(r);
  AllanPlot plot;
  plot.title = "allanlab avar: " + r.record.path + ", " + r.record.column + " (" +
               std::to_string(r.summary.num_samples) + " samples at " +
               ShortestDecimal(r.record.sample_clock.rate_hz()) + " Hz)";
  plot.y_label = DeviationName(s) + " [" + unit + "]";
  PlotSeries series{StatisticDescription(s) + " (deviation)", PlotStyle::kPoints, {}, {}, {}, {}};
  bool bars = false;
  for (const AvarRow& row : AvarRows(r)) {
    series.x.push_back(row.tau_s);
    series.y.push_back(row.dev);
    series.y_low.push_back(row.has_interval ? row.dev_low : NAN);
    series.y_high.push_back(row.has_interval ? row.dev_high : NAN);
    bars |= row.has_interval;
  }
  if (bars) series.title += ", " + Percent(r.summary.options.confidence) + " interval";
  plot.series = {std::move(series)};
  plot.guide_series = 0;
  return plot;
}

}  // namespace allanlab::app
