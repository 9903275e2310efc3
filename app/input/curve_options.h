#pragma once
// The command-line side of a published curve (app/input/curve_table.h), shared by `fit` and
// `diagnose`: --curve CSV, --curve-column, --curve-units, --record-length, with --rate (the
// record's options) as the sample rate the curve was computed at.
#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "app/reports/avar_report.h"
#include "app/input/curve_table.h"

namespace allanlab::app {

struct CurveCommandOptions {
  std::string path;  // --curve; empty: not in curve mode
  std::string column = "adev_x";
  std::string units = "deg/h";
  std::optional<double> record_length_s;
};

// Registers --curve, --curve-column, --curve-units and --record-length on `cmd`.
void AddCurveOptions(CLI::App* cmd, CurveCommandOptions* options);

// Reads the curve `options` name at `rate_hz` (--rate). Returns kExitOk, or the exit code with
// *error set: 2 when --record-length or --rate is missing or not > 0 or the units are unknown, else
// as ReadCurveTable.
int ReadCurveFromOptions(const CurveCommandOptions& options, std::optional<double> rate_hz,
                         CurveTable* table, std::string* error);

// The table as the report of a record's curve, for the commands that print, plot and fit an
// AvarReport: overlapping AVAR points without intervals, the record named by the curve file.
AvarReport ReportOfCurve(const CurveCommandOptions& options, const CurveTable& table);

// "adev.csv column adev_x (deg/h), record 7200 s at 200 Hz" for provenance.
std::string DescribeCurve(const CurveCommandOptions& options, double rate_hz);

}  // namespace allanlab::app
