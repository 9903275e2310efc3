#pragma once
// Reads one sample column of a recorded file, whatever its container: text (CSV, TSV, ';' or
// whitespace columns; rules in app/input/text_record_parser.h) or raw little-endian float32/float64,
// each plain, gzip or xz compressed (app/input/byte_source.h: decompressed by streaming, never held
// whole). Values are streamed to a sink in file order, so a record larger than memory can be
// consumed in one pass (`allanlab avar --stream`); ReadRecordValues collects them instead. The rows
// of an uncompressed text record are parsed in two threads where a second core may be used
// (common/piece_sharing.h, PieceSharing::Useful) and the record is larger than a MB
// (TextRecordParser::UseTwoThreads): the values, messages and line numbers are those of one.
//
// The sample rate comes from the time column (header t, t_s, time, time_s or timestamp, in
// seconds: 1 / the nominal step of app/input/time_steps.h, rounded to 10 significant digits) or from
// --rate. Both given: they must agree to
// kRateTolerance (relative), and --rate is used. Steps off the nominal period are counted and the
// worst gap kept (RecordInfo::time), for the caller to report.
//
// Units (app/input/stated_units.h): what the file states (the value column's name, a `# units:` line
// before the first data row, a raw record's sidecar JSON, app/input/raw_sidecar.h) and --units must
// agree, and one of them must say it; RecordInfo::units is set before the sink sees a value. A raw
// record's sidecar also gives the sample rate (--rate must then agree) and the sample count and
// type, which the file must match.
//
// PATH "-" is standard input (text or raw, plain, gzip or xz; no sidecar).
//
// A ROS bag (MCAP, ROS 2 sqlite3 .db3 or ROS 1 .bag, or a ROS 2 bag directory; recognised by its
// first bytes) is read as the text record of its sensor_msgs/Imu topic (app/input/ros_bag.h): columns
// time_s, angular_velocity.x/y/z (rad/s) and linear_acceleration.x/y/z (m/s^2).
//
// Failures (RecordError): exit code 2 (kExitUsageError) when the command line does not fit the
// file (--column names no column or an index out of range, no time column and no --rate, --rate
// disagrees with the time column or the sidecar, --format with the sidecar's type, units stated
// nowhere or --units contradicting the file); 1 (kExitRuntimeError) for everything about the file
// itself (missing/unreadable, corrupt or truncated compression, not text, no data rows, a value
// that is not a number, non-finite values without drop_nonfinite, time not increasing, fewer than
// min_samples samples, a count or units the sidecar contradicts, a unit allanlab does not read).
// Messages are one line and start with the file's path ("stdin" for "-").
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "app/input/byte_source.h"
#include "app/input/constant_stretch.h"
#include "app/input/imu_columns.h"
#include "app/input/time_steps.h"
#include "common/sample_clock.h"
#include "estimators/avar_summary.h"

namespace allanlab::app {

enum class RecordFormat { kText, kFloat32, kFloat64 };

// "text", "f32", "f64" (the --format spellings).
bool ParseRecordFormat(std::string_view text, RecordFormat* format, std::string* why);
std::string_view RecordFormatName(RecordFormat format);

inline constexpr double kRateTolerance = 1e-3;
// Non-finite values listed by line (text) or index (raw) in an error message.
inline constexpr int kListedNonFinite = 5;

struct RecordReaderOptions {
  std::string path;
  RecordFormat format = RecordFormat::kText;
  // --format not given: when a sidecar (app/input/raw_sidecar.h) gives dtype <f8 or <f4, the file is
  // read as raw float64 / float32 (`allanlab avar r.f64` after `simulate --format f64 -o r.f64`).
  bool format_from_sidecar = false;
  std::string column;             // text only: header name or 0-based index; empty = first data
  std::optional<double> rate_hz;  // --rate [Hz], finite and > 0 (checked by the caller)
  // --time-units: seconds per unit of the time column, overriding the unit its name implies
  // (t_ms, time_ns, %time, ...; bare t, time, timestamp are seconds). Finite and > 0.
  std::optional<double> time_unit_s;
  bool drop_nonfinite = false;    // skip rows whose value (or time) is NaN/inf, and count them
  std::int64_t min_samples = 3;   // fewer kept samples is an error
  estimators::InputKind kind = estimators::InputKind::kRate;  // what the samples are
  std::string units;  // --units, canonical (app/input/stated_units.h); empty when not given
  // Several columns in one pass (ReadRecordColumns; text only): header names or 0-based indices,
  // or, with `imu` and no `columns`, every gyro and accelerometer column (app/input/imu_columns.h).
  // `units` and `kind` then apply to the gyro columns; accelerometer columns take their unit from
  // their name, a '# units:' line stating an accelerometer unit, or `accel_units` (canonical,
  // app/input/accel_units.h), which must agree. A row with a non-finite value in any column is dropped
  // whole (drop_nonfinite) so that the columns stay aligned in time.
  std::vector<std::string> columns;
  bool imu = false;
  std::string accel_units;
  // A ROS bag (app/input/ros_bag.h): the sensor_msgs/Imu topic to read; empty: the bag's only one.
  // Given for a file that is not a bag: a usage error.
  std::string topic;
};

// One column of a several-column read.
struct ColumnInfo {
  std::string name;
  ImuSensor sensor = ImuSensor::kGyro;
  std::string units;         // canonical: "deg/s", "rad/s", ...; "m/s^2", "g", "mg"
  std::string units_source;  // "column Accel_X_g", "--accel-units", ...
  ConstantStretch longest_constant_stretch;  // in file units
};

struct RecordInfo {
  std::string path;
  std::string bag;  // a ROS bag's format and topic ("MCAP bag, topic /imu (...)"); empty otherwise
  Compression compression = Compression::kNone;
  RecordFormat format = RecordFormat::kText;
  bool has_header = false;
  std::string column;        // "Gyro_X", "column 2" (text without header) or "float64 samples"
  std::string time_column;   // empty when the rate did not come from a time column
  bool time_column_guessed = false;  // a headerless first column read as time (it increases)
  std::string units;         // canonical: "deg/s", "rad/s", "deg/h"; "deg", "rad", "arcsec"
  std::string units_source;  // "column rate_rad_per_s", "the '# units:' line", "--units", ...
  double time_unit_s = 1.0;  // seconds per unit of the time column
  std::int64_t lines = 0;    // text: physical lines read
  std::int64_t samples = 0;  // values passed to the sink
  std::int64_t dropped_nonfinite = 0;  // rows skipped by drop_nonfinite
  SampleClock sample_clock;  // the record's, once rate_source is set
  // "--rate", "time column t_s", "--rate (time column t_s agrees)" or "sidecar r.f64.json";
  // empty until the rate is known.
  std::string rate_source;
  TimeSteps::Summary time;  // the time column's steps (samples == 0 without one)
  ConstantStretch longest_constant_stretch;  // of the kept values, in file units
  // ReadRecordColumns: one per column, in the order asked (column, units, units_source and
  // longest_constant_stretch above then describe the first).
  std::vector<ColumnInfo> columns;
};

struct RecordError {
  int exit_code = 0;
  std::string message;
};

// Streams every kept value to `sink`, in order. The sink never sees a non-finite value. On
// failure the sink may already have received values; the caller discards its state.
// `block_sink` (optional) takes runs of a raw record's values at once instead of `sink` (the
// same values in the same order: a call per block, not per value).
using BlockSink = std::function<void(std::span<const double>)>;
bool ReadRecord(const RecordReaderOptions& options, const std::function<void(double)>& sink,
                RecordInfo* info, RecordError* error, const BlockSink* block_sink = nullptr);

// ReadRecord into a vector: `leading_zeros` zeros, then the kept values. A leading spare slot
// (kSpareSlot) lets estimators::ComputeAvarOnStorage integrate the record where it lies.
inline constexpr std::size_t kSpareSlot = 1;
bool ReadRecordValues(const RecordReaderOptions& options, std::vector<double>* values,
                      RecordInfo* info, RecordError* error, std::size_t leading_zeros = 0);

// The same for a raw float64 record used where it lies: a regular, uncompressed file of whole
// samples, read without --drop-nonfinite, is mapped read-only (app/input/mapped_file.h) and
// checked as ReadRecordValues checks it; *values are its samples, valid while *map lives. A file
// that cannot be used so (standard input, a pipe, compressed, text, float32, ...) gives
// kNotMapped with nothing reported: read it with ReadRecordValues. kFailed: *error as
// ReadRecordValues would give it. checked_blocks (optional) sees the samples a block at a time, in
// order, as each is checked (pointers into the mapping), while no value has failed the checks; the
// record's units are known by the first block.
enum class MapOutcome { kMapped, kNotMapped, kFailed };
class MappedFile;
MapOutcome MapRecordValues(const RecordReaderOptions& options, MappedFile* map, std::span<const double>* values,
                           RecordInfo* info, RecordError* error, const BlockSink* checked_blocks = nullptr);

// MapRecordValues with the checks of the samples (every one finite; the longest constant
// stretch) left to the caller, for another thread to make while this one uses the samples:
// *checks makes them and gives what MapRecordValues would have given (false with *error when a
// value is not finite), handing each block that passes to checked_blocks (optional). Until it has
// returned true the samples may not be finite, and info->samples and
// info->longest_constant_stretch are not final (it writes no other field of *info). A failure
// MapRecordValues would report after the checks is reported here, after them. *map, *values and
// *info must outlive *checks.
using MappedRecordChecks = std::function<bool(const BlockSink* checked_blocks, RecordError* error)>;
MapOutcome MapRecordValuesUnchecked(const RecordReaderOptions& options, MappedFile* map,
                                    std::span<const double>* values, RecordInfo* info, RecordError* error,
                                    MappedRecordChecks* checks);

// Several columns (options.columns or options.imu) read in one pass: values[k] holds column k's
// kept samples in file units, every column the same length.
bool ReadRecordColumns(const RecordReaderOptions& options, std::vector<std::vector<double>>* values,
                       RecordInfo* info, RecordError* error);

// The same read streamed: each kept row (one value per column, in file units) goes to `row_sink`.
// info->columns (names, sensors, units) is set before the first row; the sample rate only at the
// end. On failure the sink may already have received rows.
bool ReadRecordRows(const RecordReaderOptions& options, const std::function<void(std::span<const double>)>& row_sink,
                    RecordInfo* info, RecordError* error);

}  // namespace allanlab::app
