#pragma once
// `allanlab avar FILE`: the Allan-family curve of a recorded rate (or angle) column with
// confidence intervals, as a table on stdout and optionally JSON, CSV (both with provenance) and
// a PNG diagram. The record is read and its curve computed by app/input/record_curve.h.
// In memory by default: estimators/avar.h (every statistic, tau grid and interval). With
// --stream, one pass in bounded memory: estimators/streaming_avar.h (octave taus, overlapping or
// non-overlapping AVAR, simple or no interval), for records larger than memory.
//
// Units: input as the file states them or --units (rate: deg/s, deg/h, rad/s; angle: deg, rad,
// arcsec; app/input/stated_units.h: both must agree, one must say), converted to SI on reading; output
// in --out-units (default deg/h). Tau in seconds.
//
// Exit codes (app/commands/subcommand.h): 2 for a wrong command line or value (unknown unit, estimator,
// tau grid, CI method or format, a confidence outside (0, 1), a --rate not finite and > 0 or
// disagreeing with the time column, no rate at all, a --column the file does not have, an option
// --stream cannot do, two outputs naming one file); 1 for a file that cannot be read or whose
// content is bad (see app/input/record_reader.h), an estimator failure, gnuplot missing or failing, an
// output that cannot be written. Errors are one line "allanlab avar: error: ..."; warnings
// (irregular time steps, dropped values) are "allanlab avar: warning: ..." lines on stderr.
// Outputs go through AtomicFile and are committed together at the end: a failed run leaves no
// new or changed file.
#include <CLI/CLI.hpp>
#include <string>

#include "app/commands/subcommand.h"
#include "app/input/record_curve.h"

namespace allanlab::app {

struct AvarCommandOptions {
  RecordCurveOptions record;  // FILE, what to read and which curve (app/input/record_curve.h)
  std::string json_path, csv_path, plot_path;
};

Subcommand AddAvarCommand(CLI::App* parent);
int RunAvar(const AvarCommandOptions& options, const std::string& command_line);

}  // namespace allanlab::app
