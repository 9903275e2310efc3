#include "app/commands/avar_command.h"

#include <iostream>
#include <memory>
#include <utility>
#include <vector>

#include "app/input/rate_units.h"
#include "app/input/record_curve.h"
#include "app/input/record_reader.h"
#include "app/reports/allan_plot.h"
#include "common/atomic_file.h"
#include "app/reports/avar_report.h"
#include "app/reports/imu_report.h"
#include "app/reports/output_paths.h"
#include "app/reports/provenance.h"
#include "common/number_text.h"
#include "estimators/allan_family.h"

namespace allanlab::app {
namespace {

constexpr const char* kCommand = "avar";

using Failure = CommandFailure;
Failure Usage(std::string message) { return UsageFailure(std::move(message)); }
Failure Runtime(std::string message) { return RuntimeFailure(std::move(message)); }

// Where the curve came from and how it was computed.
Provenance AvarProvenance(const RecordCurveOptions& o, const AvarReport& report, const std::string& command_line) {
  Provenance p = MakeProvenance(kCommand, command_line);
  const RecordInfo& info = report.record;
  p.Add("input", info.path);
  p.Add("format", info.bag.empty() ? std::string(RecordFormatName(info.format)) + ", compression " +
                                          std::string(CompressionName(info.compression))
                                    : info.bag);
  p.Add("column", info.column);
  p.Add("type", o.type);
  p.Add("units", info.units + " in (" + info.units_source + "), " +
                     std::string(RateUnitName(report.output_unit)) + " out");
  p.Add("samples", std::to_string(info.samples) + " read, " +
                       std::to_string(report.summary.num_samples) + " rate samples used");
  p.Add("sample_rate", ShortestDecimal(info.sample_clock.rate_hz()) + " Hz (" + info.rate_source + ")");
  if (info.dropped_nonfinite > 0) {
    p.Add("dropped_nonfinite", std::to_string(info.dropped_nonfinite));
  }
  if (!info.time_column.empty()) {
    p.Add("irregular_time_steps", std::to_string(info.time.irregular_steps));
  }
  p.Add("estimator", std::string(estimators::StatisticId(report.summary.options.statistic)) +
                         (report.streamed ? " (--stream, exact overlap up to m = " +
                                                std::to_string(o.stream_exact_max_m) + ")"
                                          : ""));
  p.Add("taus", o.taus);
  p.Add("interval", o.ci.value_or(o.stream ? "simple" : "auto") + " at confidence " +
                        ShortestDecimal(report.summary.options.confidence));

  return p;
}

// Several columns: a table each on stdout, one JSON, CSV and PNG for all (app/reports/imu_report.h).
std::optional<Failure> AvarSeveral(const AvarCommandOptions& o, const std::string& command_line, AtomicFile* json, AtomicFile* csv,
                                   AtomicFile* png) {
  std::vector<AvarReport> reports;
  std::string why;
  if (const int code = ComputeCurvesFromFile(o.record, kCommand, &reports, &why); code != kExitOk) {
    return Failure{code, why};
  }
  for (AvarReport& r : reports) r.provenance = AvarProvenance(o.record, r, command_line);
  Provenance p = reports.front().provenance;
  p.Add("columns", DescribeColumns(reports));
  for (std::size_t k = 0; k < reports.size(); ++k) {
    if (k > 0) std::cout << "\n";
    WriteAvarTable(std::cout, reports[k]);
  }
  std::cout.flush();
  if (json->is_open()) json->stream() << ImuAvarJson(reports, p).dump(2) << "\n";
  if (csv->is_open()) WriteImuAvarCsv(csv->stream(), reports, p);
  if (png->is_open() && !RenderAllanPlots(ImuAvarPlots(reports, "allanlab avar"), png, &why)) return Runtime(why);
  for (AtomicFile* file : {json, csv, png}) {
    if (file->is_open() && !file->Commit(&why)) return Runtime(why);
  }
  return std::nullopt;
}

std::optional<Failure> Avar(const AvarCommandOptions& o, const std::string& command_line) {
  // 1. The command line on its own.
  std::string why;
  if (const int code = CheckRecordCurveOptions(o.record, &why); code != kExitOk) return Failure{code, why};

  // 2. Every output opened before the work: a bad path or a missing gnuplot costs nothing.
  std::vector<std::pair<std::string, std::string>> outputs = {{"FILE", o.record.path}};
  if (!o.json_path.empty()) outputs.emplace_back("--json", o.json_path);
  if (!o.csv_path.empty()) outputs.emplace_back("--csv", o.csv_path);
  if (!o.plot_path.empty()) outputs.emplace_back("--plot", o.plot_path);
  if (!CheckDistinctOutputs(outputs, &why)) return Usage(why);
  if (!o.plot_path.empty() && !FindGnuplot(&why)) return Runtime(why);
  AtomicFile json, csv, png;
  if (!o.json_path.empty() && !json.Open(o.json_path, &why)) return Runtime(why);
  if (!o.csv_path.empty() && !csv.Open(o.csv_path, &why)) return Runtime(why);
  if (!o.plot_path.empty() && !png.Open(o.plot_path, &why)) return Runtime(why);

  if (SeveralColumns(o.record)) return AvarSeveral(o, command_line, &json, &csv, &png);

  // 3. The record and its curve.
  AvarReport report;
  if (const int code = ComputeCurveFromFile(o.record, kCommand, &report, &why); code != kExitOk) {
    return Failure{code, why};
  }
  report.provenance = AvarProvenance(o.record, report, command_line);

  // 4. Outputs: stdout first, files committed last and together.
  WriteAvarTable(std::cout, report);
  std::cout.flush();
  if (json.is_open()) json.stream() << AvarJson(report).dump(2) << "\n";
  if (csv.is_open()) WriteAvarCsv(csv.stream(), report);
  if (png.is_open() && !RenderAllanPlot(AvarPlot(report), &png, &why)) return Runtime(why);
  for (AtomicFile* file : {&json, &csv, &png}) {
    if (file->is_open() && !file->Commit(&why)) return Runtime(why);
  }
  return std::nullopt;
}

}  // namespace

Subcommand AddAvarCommand(CLI::App* parent) {
  auto options = std::make_shared<AvarCommandOptions>();
  CLI::App* cmd = parent->add_subcommand(
      kCommand,
      "Allan-family curve of a recorded gyro rate (or angle) column with confidence intervals: "
      "a table on stdout, optionally JSON, CSV and an Allan diagram.");
  AddRecordCurveOptions(cmd, &options->record);
  cmd->add_option("--estimator", options->record.estimator,
                  "overlapping (default), nonoverlapping, modified, hadamard, "
                  "hadamard_nonoverlapping, total or time")
      ->type_name("NAME");
  cmd->add_option("--json", options->json_path, "also write the results as JSON with provenance")
      ->type_name("OUT.json");
  cmd->add_option("--csv", options->csv_path, "also write the results as CSV with provenance")
      ->type_name("OUT.csv");
  cmd->add_option("--plot", options->plot_path,
                  "also draw the log-log diagram with interval bars and slope guides (PNG, "
                  "needs gnuplot)")
      ->type_name("OUT.png");
  cmd->add_flag("--stream", options->record.stream,
                "one pass in bounded memory for records larger than memory (every column of "
                "--columns/--imu in the same pass): octave taus, "
                "overlapping or nonoverlapping AVAR, --ci simple or none");
  cmd->add_option("--stream-exact-m", options->record.stream_exact_max_m,
                  "with --stream: overlapping AVAR uses every window start up to this m (a power "
                  "of two, default 16384; state ~32 bytes x M per octave), every m/M-th above")
      ->type_name("M");
  cmd->footer(
      "Output files are written to a temporary file and renamed into place only when the whole "
      "run succeeds.\nExit status: 0 ok, 1 bad or unreadable file, I/O or gnuplot error, 2 usage "
      "error.");
  return {cmd,
          [options](const std::string& command_line) { return RunAvar(*options, command_line); }};
}

int RunAvar(const AvarCommandOptions& options, const std::string& command_line) {
  return RunCommand(kCommand, " (for records larger than memory, use --stream)", [&] { return Avar(options, command_line); });
}

}  // namespace allanlab::app
