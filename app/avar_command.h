#pragma once
// `allanlab avar FILE`: the Allan-family curve of a recorded rate (or angle) column with
// confidence intervals, as a table on stdout and optionally JSON, CSV (both with provenance) and
// a PNG diagram. The record is read by app/record_reader.h (text, f32, f64; plain, gzip, xz).
// In memory by default: estimators/avar.h (every statistic, tau grid and interval). With
// --stream, one pass in bounded memory: estimators/streaming_avar.h (octave taus, overlapping or
// non-overlapping AVAR, simple or no interval), for records larger than memory.
//
// Units: input as the file states them or --units (rate: deg/s, deg/h, rad/s; angle: deg, rad,
// arcsec; app/stated_units.h: both must agree, one must say), converted to SI on reading; output
// in --out-units (default deg/h). Tau in seconds.
//
// Exit codes (app/subcommand.h): 2 for a wrong command line or value (unknown unit, estimator,
// tau grid, CI method or format, a confidence outside (0, 1), a --rate not finite and > 0 or
// disagreeing with the time column, no rate at all, a --column the file does not have, an option
// --stream cannot do, two outputs naming one file); 1 for a file that cannot be read or whose
// content is bad (see app/record_reader.h), an estimator failure, gnuplot missing or failing, an
// output that cannot be written. Errors are one line "allanlab avar: error: ..."; warnings
// (irregular time steps, dropped values) are "allanlab avar: warning: ..." lines on stderr.
// Outputs go through AtomicFile and are committed together at the end: a failed run leaves no
// new or changed file.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "app/subcommand.h"

namespace allanlab::app {

struct AvarReport;
struct RecordInfo;

struct AvarCommandOptions {
  std::string path;
  std::string column;  // a comma list reads several columns, as `columns`
  // Several columns in one pass (app/imu_columns.h): a comma list, or --imu for every gyro and
  // accelerometer column named as such. Each gets its own curve.
  std::string columns;
  bool imu = false;
  std::string accel_units;             // empty: as the file states them
  std::string accel_out_units = "mg";  // m/s^2, g or mg
  std::string units;  // empty: as the file states them (an error when it does not)
  std::string out_units = "deg/h";
  std::optional<double> rate_hz;
  std::string topic;  // --topic: a ROS bag's sensor_msgs/Imu topic (app/ros_bag.h)
  std::string time_units;  // --time-units s|ms|us|ns; empty: from the time column's name
  std::string type = "rate";
  std::string estimator = "overlapping";
  std::string taus = "octave";
  double confidence = 0.683;
  std::optional<std::string> ci;  // unset: gr, or simple with --stream
  std::string json_path, csv_path, plot_path;
  std::string format;  // text, f32, f64 (the input record); empty: text unless a sidecar says raw
  bool drop_nonfinite = false;
  bool stream = false;
  std::int64_t stream_exact_max_m = std::int64_t{1} << 14;
  // Not a command-line option: set by `fit` (estimators::AvarOptions::identification_max_averages).
  std::int64_t identification_max_averages = 0;
};

Subcommand AddAvarCommand(CLI::App* parent);
int RunAvar(const AvarCommandOptions& options, const std::string& command_line);

// Shared with commands that start from a recorded curve (`fit`): the options that read a record
// and choose its curve (FILE, --column, --units, --out-units, --rate, --type, --taus,
// --confidence, --ci, --format, --drop-nonfinite) ...
void AddRecordCurveOptions(CLI::App* cmd, AvarCommandOptions* options);
// ... and reading + computing it in memory as `avar` does (warnings printed under `command`).
// Returns kExitOk, or the exit code with *error set. report->provenance is left to the caller.
int ComputeCurveFromFile(const AvarCommandOptions& options, const std::string& command,
                         AvarReport* report, std::string* error);

// A record already in memory (the Python module): `values` in options.units (rate or angle, as
// options.type), sampled at *options.rate_hz; options.path names it in messages. The curve is
// computed as ComputeCurveFromFile computes a file's; the same checks give the same errors (units
// and rate required, every value finite, enough samples). Nothing is printed.
int ComputeCurveFromSamples(const AvarCommandOptions& options, std::vector<double> values,
                            AvarReport* report, std::string* error);
// ... and its rate in rad/s as ReadRateFromFile gives a file's (angle input differenced).
int RateFromSamples(const AvarCommandOptions& options, std::vector<double>* values, RecordInfo* info,
                    std::string* error);

// Several columns asked (--columns, a comma list in --column, or --imu), or one accelerometer
// axis by name (--column Accel_X): read as a column of an IMU, in its sensor's units.
bool SeveralColumns(const AvarCommandOptions& options);
// Every asked column's curve, the record read once; one report per column in the order asked,
// each with the column's name, units and sensor in report->record / ->sensor (warnings about the
// record printed once, about a column's constant stretch per column).
int ComputeCurvesFromFile(const AvarCommandOptions& options, const std::string& command,
                          std::vector<AvarReport>* reports, std::string* error);

// Reading the record alone, as `avar` reads it, converted to rate samples in rad/s (angle input
// differenced); *info describes the file (sample rate, dropped values, time steps). Returns
// kExitOk, or the exit code with *error set. Warnings are printed under `command`.
int ReadRateFromFile(const AvarCommandOptions& options, const std::string& command,
                     std::vector<double>* rate_rad_per_s, RecordInfo* info, std::string* error);

// Several columns read once as ReadRateFromFile reads one: rates[k] is column k in SI (a gyro's
// rate in rad/s, angle input differenced; an accelerometer's acceleration in m/s^2);
// info->columns names each column, its sensor and units.
int ReadRatesFromFile(const AvarCommandOptions& options, const std::string& command,
                      std::vector<std::vector<double>>* rates, RecordInfo* info, std::string* error);

}  // namespace allanlab::app
