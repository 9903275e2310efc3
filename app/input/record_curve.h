#pragma once
// A recorded column read as every command reads it, and its Allan-family curve. The record is
// read by app/input/record_reader.h (text, f32, f64, ROS bags; plain, gzip, xz) and converted
// to SI; the curve is computed in memory (estimators/avar.h: every statistic, tau grid and
// interval) or, with `stream`, in one pass in bounded memory (estimators/streaming_avar.h:
// octave taus, overlapping or non-overlapping AVAR, simple or no interval).
//
// Units: input as the file states them or `units` (rate: deg/s, deg/h or rad/s; angle: deg, rad
// or arcsec; app/input/stated_units.h: both must agree, one must say), converted to SI on
// reading; accelerometer columns in m/s^2. Tau in seconds.
//
// Exit codes (app/failure.h): 2 for a wrong option or value (unknown unit, estimator, tau grid,
// CI method or format, a confidence outside (0, 1), a rate not finite and > 0 or disagreeing
// with the time column, no rate at all, a column the file does not have, an option the stream
// cannot do); 1 for a file that cannot be read or whose content is bad (app/input/record_reader.h)
// or an estimator failure.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "app/failure.h"
#include "estimators/avar_options.h"

namespace allanlab::app {

struct AvarReport;
struct RecordInfo;

struct RecordCurveOptions {
  std::string path;
  std::string column;  // a comma list reads several columns, as `columns`
  // Several columns in one pass (app/input/imu_columns.h): a comma list, or --imu for every gyro and
  // accelerometer column named as such. Each gets its own curve.
  std::string columns;
  bool imu = false;
  std::string accel_units;             // empty: as the file states them
  std::string accel_out_units = "mg";  // m/s^2, g or mg
  std::string units;  // empty: as the file states them (an error when it does not)
  std::string out_units = "deg/h";
  std::optional<double> rate_hz;
  std::string topic;  // --topic: a ROS bag's sensor_msgs/Imu topic (app/input/ros_bag.h)
  std::string time_units;  // --time-units s|ms|us|ns; empty: from the time column's name
  std::string type = "rate";
  std::string estimator = "overlapping";
  std::string taus = "octave";
  double confidence = 0.683;
  std::optional<std::string> ci;  // unset: gr, or simple with --stream
  std::string format;  // text, f32, f64 (the input record); empty: text unless a sidecar says raw
  bool drop_nonfinite = false;
  bool stream = false;
  std::int64_t stream_exact_max_m = std::int64_t{1} << 14;
  // Not a command-line option (estimators::AvarOptions::identification_max_averages).
  std::int64_t identification_max_averages = estimators::kIdentificationMaxAverages;
};

// The command-line options that read a record and choose its curve (FILE, --column, --columns,
// --imu, --units, --out-units, --accel-units, --accel-out-units, --topic, --rate, --time-units,
// --type, --taus, --confidence, --ci, --format, --drop-nonfinite). --estimator and --stream are
// added by `avar` alone.
void AddRecordCurveOptions(CLI::App* cmd, RecordCurveOptions* options);
// The options checked on their own, before any file is opened: kExitOk, or the exit code with
// *error set.
int CheckRecordCurveOptions(const RecordCurveOptions& options, std::string* error);
// One column read and its curve computed, in memory or (options.stream) in one pass; warnings
// printed under `command`. Returns kExitOk, or the exit code with *error set.
// report->provenance is left to the caller.
int ComputeCurveFromFile(const RecordCurveOptions& options, const std::string& command,
                         AvarReport* report, std::string* error);

// A record already in memory (the Python module): `values` in options.units (rate or angle, as
// options.type), sampled at *options.rate_hz; options.path names it in messages. The curve is
// computed as ComputeCurveFromFile computes a file's; the same checks give the same errors (units
// and rate required, every value finite, enough samples). Nothing is printed.
int ComputeCurveFromSamples(const RecordCurveOptions& options, std::vector<double> values,
                            AvarReport* report, std::string* error);
// ... and its rate in rad/s as ReadRateFromFile gives a file's (angle input differenced).
int RateFromSamples(const RecordCurveOptions& options, std::vector<double>* values, RecordInfo* info,
                    std::string* error);

// Several columns asked (--columns, a comma list in --column, or --imu), or one accelerometer
// axis by name (--column Accel_X): read as a column of an IMU, in its sensor's units.
bool SeveralColumns(const RecordCurveOptions& options);
// Every asked column's curve, the record read once (in one streamed pass with options.stream); one report per column in the order asked,
// each with the column's name, units and sensor in report->record / ->sensor (warnings about the
// record printed once, about a column's constant stretch per column).
int ComputeCurvesFromFile(const RecordCurveOptions& options, const std::string& command,
                          std::vector<AvarReport>* reports, std::string* error);

// Reading the record alone, as `avar` reads it, converted to rate samples in rad/s (angle input
// differenced); *info describes the file (sample rate, dropped values, time steps). Returns
// kExitOk, or the exit code with *error set. Warnings are printed under `command`.
int ReadRateFromFile(const RecordCurveOptions& options, const std::string& command,
                     std::vector<double>* rate_rad_per_s, RecordInfo* info, std::string* error);

// Several columns read once as ReadRateFromFile reads one: rates[k] is column k in SI (a gyro's
// rate in rad/s, angle input differenced; an accelerometer's acceleration in m/s^2);
// info->columns names each column, its sensor and units.
int ReadRatesFromFile(const RecordCurveOptions& options, const std::string& command,
                      std::vector<std::vector<double>>* rates, RecordInfo* info, std::string* error);

}  // namespace allanlab::app
