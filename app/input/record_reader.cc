#include "app/input/record_reader.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <exception>
#include <filesystem>
#include <system_error>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "app/input/accel_units.h"
#include "app/input/imu_columns.h"
#include "app/input/mapped_file.h"
#include "app/reports/provenance.h"
#include "app/input/raw_sample_decoder.h"
#include "app/input/raw_sidecar.h"
#include "app/input/read_ahead_source.h"
#include "app/input/ros_bag.h"
#include "app/input/stated_units.h"
#include "app/failure.h"
#include "app/input/text_record_parser.h"
#include "common/all_finite.h"
#include "common/huge_pages.h"
#include "common/piece_sharing.h"
#include "common/number_text.h"

namespace allanlab::app {
namespace {

constexpr std::size_t kChunkBytes = 1 << 18;
// A text chunk read in two threads: large enough that the wake-up of the helper once per chunk
// costs little (TextRecordParser::UseTwoThreads).
constexpr std::size_t kTwoThreadChunkBytes = std::size_t{1} << 22;
constexpr std::size_t kBlockValues = 4096;  // a mapped record's values checked per block
// A raw stream's blocks: a whole chunk of float64 values each, which a consumer that works in
// blocks of that size (estimators::StreamingAvar) takes where it lies instead of gathering.
constexpr std::size_t kRawStreamBlockValues = kChunkBytes / sizeof(double);

// The mean of a million printed steps carries its rounding in the last digits (100 Hz from
// t = 0.00, 0.01, ... comes out as 99.99999999999993 Hz); ten digits are more than a time column
// can resolve and less than its noise.
double RoundToSignificantDigits(double value, int digits) {
  return std::strtod(SignificantDigits(value, digits).c_str(), nullptr);
}

// Non-finite values are collected over the whole file so that the message can say how many
// there are, not just where the first one is.
class NonFiniteLog {
 public:
  void Add(std::int64_t where) {
    if (static_cast<int>(first_.size()) < kListedNonFinite) first_.push_back(where);
    ++count_;
  }
  std::int64_t count() const { return count_; }
  std::string Describe(const std::string& what, const std::string& unit_of_position) const {
    std::string list;
    for (std::size_t i = 0; i < first_.size(); ++i) {
      list += (i ? ", " : "") + std::to_string(first_[i]);
    }
    return std::to_string(count_) + " non-finite value(s) (NaN, inf or missing) in " + what +
           " at " + unit_of_position + " " + list + (count_ > kListedNonFinite ? ", ..." : "") +
           "; remove them or pass --drop-nonfinite to skip them";
  }

 private:
  std::vector<std::int64_t> first_;
  std::int64_t count_ = 0;
};

class Reader {
 public:
  // block_sink (may be null): takes runs of finite raw values at once, instead of sink.
  Reader(const RecordReaderOptions& options, const std::function<void(double)>& sink,
         RecordInfo* info, const std::function<void(std::span<const double>)>* block_sink = nullptr)
      : o_(options), sink_(sink), block_sink_(block_sink), info_(info) {}
  // Several columns: each kept row's values (one per column) go to row_sink.
  Reader(const RecordReaderOptions& options, const std::function<void(std::span<const double>)>* row_sink,
         RecordInfo* info)
      : o_(options), sink_(kNoSink), block_sink_(nullptr), row_sink_(row_sink), info_(info) {}
  // A raw float64 file mapped where it can be (MapRecordValues): *values the mapped samples.
  Reader(const RecordReaderOptions& options, MappedFile* map, std::span<const double>* values, RecordInfo* info,
         const std::function<void(std::span<const double>)>* block_sink)
      : o_(options), sink_(kNoSink), block_sink_(block_sink != nullptr ? block_sink : &kNoBlockSink), info_(info),
        map_(map), mapped_values_(values) {}
  // After Run returned false: the file was not mapped, nothing was reported (MapRecordValues).
  bool not_mapped() const { return not_mapped_; }
  // A mapped file's values are not checked by Run but by CheckMapped (MapRecordValuesUnchecked).
  void DeferChecks() { defer_checks_ = true; }
  // The checks Run deferred, as ReadMapped makes them, the checked blocks to checked_blocks.
  bool CheckMapped(const std::function<void(std::span<const double>)>* checked_blocks, RecordError* error) {
    block_sink_ = checked_blocks != nullptr ? checked_blocks : &kNoBlockSink;
    info_->samples = 0;
    return ReadMapped(error);
  }

  bool Run(RecordError* error) {
    *info_ = RecordInfo();
    info_->path = o_.path == "-" ? "stdin" : o_.path;
    std::string why;
    format_ = o_.format;
    if (o_.format_from_sidecar && o_.path != "-") {
      // No --format: a sidecar that describes raw samples says how to read the file.
      std::optional<RawSidecar> side;
      if (!ReadRawSidecar(o_.path, &side, &why)) return Runtime(error, In() + why);
      if (side && side->dtype == "<f8") format_ = RecordFormat::kFloat64;
      if (side && side->dtype == "<f4") format_ = RecordFormat::kFloat32;
      if (format_ != RecordFormat::kText && !o_.column.empty()) {
        return Usage(error, In() + "the sidecar " + side->path + " describes raw " +
                                std::string(RecordFormatName(format_)) +
                                " samples, one column: drop --column");
      }
    }
    info_->format = format_;
    if (row_sink_ != nullptr && format_ != RecordFormat::kText) {
      return Usage(error, In() + (o_.imu ? std::string("--imu") : std::string("--columns")) +
                              " applies to text records; raw " +
                              std::string(RecordFormatName(format_)) + " has one column");
    }
    if (format_ != RecordFormat::kText) {
      if (o_.path != "-" && !ReadRawSidecar(o_.path, &sidecar_, &why)) {
        return Runtime(error, In() + why);
      }
      if (!CheckSidecar(error)) return false;
      if (!o_.rate_hz && !(sidecar_ && sidecar_->sample_rate_hz)) {
        return Usage(error, In() + "raw " + std::string(RecordFormatName(format_)) +
                                " samples carry no time" +
                                (o_.path == "-" ? std::string()
                                                : " and no sidecar " + o_.path +
                                                      ".json gives their rate") +
                                ": give the sample rate with --rate HZ");
      }
      std::vector<StatedUnit> stated;
      if (sidecar_ && sidecar_->units) {
        std::string unit;
        if (!CanonicalUnit(*sidecar_->units, o_.kind, &unit, &why)) {
          return Runtime(error, In() + "the sidecar " + sidecar_->path + ": " + why);
        }
        stated.push_back({unit, "the sidecar " + sidecar_->path});
      }
      if (stated.empty() && o_.units.empty()) {
        return Usage(error, In() + "raw " + std::string(RecordFormatName(format_)) + " samples state no units" +
                                (o_.path == "-" ? std::string()
                                                : " and no sidecar " + o_.path + ".json gives them") +
                                ": give --units " +
                                (o_.kind == estimators::InputKind::kAngle ? "deg, rad or arcsec" : "deg/s, deg/h or rad/s"));
      }
      if (!ResolveStatedUnits(std::move(stated), "the samples", error)) return false;
    }
    if (map_ != nullptr) {
      if (!MapRaw()) {
        not_mapped_ = true;
        return false;
      }
      info_->compression = Compression::kNone;
      info_->column = "float64 samples";
      if (defer_checks_) {
        // The count the checks give when every value is finite; they are the caller's to make.
        info_->samples = static_cast<std::int64_t>(mapped_values_->size());
        if (Conclude(error)) return true;
        // Without deferral the checks come first, and so does their failure.
        RecordError check_error;
        if (!CheckMapped(nullptr, &check_error)) *error = check_error;
        return false;
      }
      if (!ReadMapped(error)) return false;
      return Conclude(error);
    }
    std::unique_ptr<ByteSource> source;
    if (!OpenSource(&source, error)) return false;
    info_->compression = source->compression();
    const bool ok = format_ == RecordFormat::kText ? ReadText(source.get(), error)
                                                     : ReadRaw(source.get(), error);
    if (!ok) return false;
    return Conclude(error);
  }

 private:
  // The file's bytes, or a ROS bag's Imu topic as text (app/input/ros_bag.h).
  bool OpenSource(std::unique_ptr<ByteSource>* source, RecordError* error) {
    std::string why;
    const std::optional<BagFormat> bag = o_.path == "-" ? std::nullopt : DetectBag(o_.path);
    if (bag) {
      if (format_ != RecordFormat::kText) return Usage(error, In() + "a ROS bag holds messages, not raw samples: drop --format");
      BagRecord record;
      if (const int code = OpenBagRecord(o_.path, *bag, o_.topic, &record, &why); code != kExitOk) {
        *error = {code, In() + why};
        return false;
      }
      info_->bag = record.description;
      bag_stamps_ = " (header stamps of " + record.topic + ")";
      steps_ = TimeSteps("message", -1);
      *source = std::move(record.text);
      return true;
    }
    if (!o_.topic.empty()) {
      return Usage(error, In() + "--topic reads a ROS bag (MCAP, ROS 2 .db3 or ROS 1 .bag), and this file is none");
    }
    if (!OpenByteSource(o_.path, source, &why)) return Runtime(error, why);
    // Decompression is the slowest step of a compressed record: it runs ahead in its own thread
    // while this one parses (the same bytes and errors, app/input/read_ahead_source.h).
    if ((*source)->compression() != Compression::kNone) *source = ReadAhead(std::move(*source));
    return true;
  }

  // The sidecar's type and rate against the command line (its count is checked after reading).
  bool CheckSidecar(RecordError* error) {
    if (!sidecar_) return true;
    const std::string name = "the sidecar " + sidecar_->path;
    const std::string_view expected = format_ == RecordFormat::kFloat32 ? "<f4" : "<f8";
    if (sidecar_->dtype && *sidecar_->dtype != expected) {
      return Usage(error, In() + name + " says dtype " + *sidecar_->dtype + ", not " +
                              std::string(expected) + " as --format " +
                              std::string(RecordFormatName(format_)) + " reads: fix --format");
    }
    const std::optional<double>& side = sidecar_->sample_rate_hz;
    if (side && o_.rate_hz && std::abs(*o_.rate_hz - *side) > kRateTolerance * *side) {
      return Usage(error, In() + "--rate " + ShortestDecimal(*o_.rate_hz) +
                              " Hz disagrees with " + name + " (" + ShortestDecimal(*side) +
                              " Hz); drop --rate or fix it");
    }
    return true;
  }

  // The file's statements of the units (`stated`) and --units reduced to one, into *info_.
  bool ResolveStatedUnits(std::vector<StatedUnit> stated, const std::string& what,
                          RecordError* error) {
    if (!o_.units.empty()) stated.push_back({o_.units, "--units"});
    StatedUnit resolved;
    std::string why;
    if (!ResolveUnits(stated, o_.kind, what, &resolved, &why)) return Usage(error, In() + why);
    info_->units = resolved.unit;
    info_->units_source = resolved.source;
    return true;
  }

  // What a text record says about its units, once its header and leading comments are known.
  bool ResolveTextUnits(const TextRecordParser& parser, RecordError* error) {
    std::vector<StatedUnit> stated;
    std::string why;
    if (parser.has_header()) {
      std::optional<StatedUnit> from_name;
      if (!UnitFromColumnName(parser.value_column(), o_.kind, &from_name, &why)) {
        return Runtime(error, In() + why);
      }
      if (from_name) stated.push_back(*from_name);
    }
    if (const std::string line = parser.LeadingComment("units"); !line.empty()) {
      std::string unit;
      if (!CanonicalUnit(line, o_.kind, &unit, &why)) {
        return Runtime(error, In() + "the '# units:' line: " + why);
      }
      stated.push_back({unit, "the '# units: " + line + "' line"});
    }
    return ResolveStatedUnits(std::move(stated), "column " + parser.value_column(), error);
  }

  // Every column's units (several-column read): a gyro column as ResolveTextUnits, an
  // accelerometer column from its name, a '# units:' line naming an accelerometer unit, and
  // --accel-units. A '# units:' line speaks for the columns whose kind its unit fits.
  bool ResolveColumnUnits(const TextRecordParser& parser, RecordError* error) {
    const std::string line = parser.LeadingComment("units");
    std::string why;
    AccelUnit accel_line_unit;
    const bool line_is_accel = !line.empty() && ParseAccelUnit(line, &accel_line_unit, nullptr);
    std::string gyro_line_unit;
    const bool line_is_gyro = !line.empty() && CanonicalUnit(line, o_.kind, &gyro_line_unit, &why);
    if (!line.empty() && !line_is_accel && !line_is_gyro) {
      return Runtime(error, In() + "the '# units:' line: '" + line +
                                "' is neither a gyro unit (deg/s, deg/h, rad/s) nor an "
                                "accelerometer unit (m/s^2, g, mg)");
    }
    info_->columns.clear();
    for (const std::string& name : parser.value_columns()) {
      ColumnInfo c;
      c.name = name;
      c.sensor = ImuSensorOfColumn(name).value_or(ImuSensor::kGyro);
      std::vector<StatedUnit> stated;
      if (c.sensor == ImuSensor::kGyro) {
        if (parser.has_header()) {
          std::optional<StatedUnit> from_name;
          if (!UnitFromColumnName(name, o_.kind, &from_name, &why)) return Runtime(error, In() + why);
          if (from_name) stated.push_back(*from_name);
        }
        if (line_is_gyro) stated.push_back({gyro_line_unit, "the '# units: " + line + "' line"});
        if (!o_.units.empty()) stated.push_back({o_.units, "--units"});
        StatedUnit resolved;
        if (!ResolveUnits(stated, o_.kind, "gyro column " + name, &resolved, &why)) {
          return Usage(error, In() + why);
        }
        c.units = resolved.unit;
        c.units_source = resolved.source;
      } else {
        if (const std::string unit = AccelUnitFromColumnName(name); !unit.empty()) {
          stated.push_back({unit, "column " + name});
        }
        if (line_is_accel) {
          stated.push_back({std::string(AccelUnitName(accel_line_unit)), "the '# units: " + line + "' line"});
        }
        if (!o_.accel_units.empty()) stated.push_back({o_.accel_units, "--accel-units"});
        if (stated.empty()) {
          return Usage(error, In() + "the units of accelerometer column " + name +
                                  " are not stated in the file (a unit in the column name such as "
                                  "Accel_X_g or acc_x_mps2, or a '# units:' line): give "
                                  "--accel-units m/s^2, g or mg");
        }
        for (std::size_t i = 1; i < stated.size(); ++i) {
          if (stated[i].unit != stated[0].unit) {
            return Usage(error, In() + stated[i].source + " (" + stated[i].unit + ") contradicts " +
                                    stated[0].source + " (" + stated[0].unit + ")");
          }
        }
        c.units = stated[0].unit;
        c.units_source = stated[0].source;
      }
      info_->columns.push_back(std::move(c));
    }
    info_->units = info_->columns.front().units;
    info_->units_source = info_->columns.front().units_source;
    stretches_.assign(info_->columns.size(), ConstantStretchTracker());
    return true;
  }

  // A row of a several-column read: dropped or logged whole when any value is not finite.
  void AcceptRow(std::span<const double> values, std::int64_t line) {
    bool finite = true;
    for (double v : values) finite &= std::isfinite(v);
    if (!finite) {
      if (o_.drop_nonfinite) {
        ++info_->dropped_nonfinite;
      } else {
        nonfinite_.Add(line);
      }
      return;
    }
    ++info_->samples;
    for (std::size_t k = 0; k < values.size(); ++k) stretches_[k].Add(values[k]);
    if (nonfinite_.count() == 0) (*row_sink_)(values);
  }

  bool Usage(RecordError* error, const std::string& message) {
    *error = {kExitUsageError, message};
    return false;
  }
  bool Runtime(RecordError* error, const std::string& message) {
    *error = {kExitRuntimeError, message};
    return false;
  }
  std::string In() const { return (o_.path == "-" ? std::string("stdin") : o_.path) + ": "; }

  // A non-finite row is dropped or logged; a finite one is passed on (until the first logged
  // non-finite value: the record will fail, so the sink need not see more).
  void Accept(double value, std::int64_t where) {
    if (!std::isfinite(value)) {
      if (o_.drop_nonfinite) {
        ++info_->dropped_nonfinite;
      } else {
        nonfinite_.Add(where);
      }
      return;
    }
    ++info_->samples;
    stretch_.Add(value);  // info_->longest_constant_stretch is set from it when the read ends
    if (nonfinite_.count() == 0) sink_(value);
  }

  bool ReadText(ByteSource* source, RecordError* error) {
    std::string stop;  // why the sink stopped the parser
    bool stop_is_usage = false;
    RecordError units_error;
    TextRecordParser* parser_ptr = nullptr;
    const bool several = row_sink_ != nullptr;
    TextRecordParser::ColumnChooser chooser;
    if (several && o_.imu && o_.columns.empty()) chooser = ChooseImuColumns;
    // A time step TimeSteps refused: its message, in `stop`.
    const auto step_refused = [&] {
      if (parser_ptr->time_column_guessed()) {
        stop += " (the file has no header and its first column increased over its first " +
                std::to_string(TextRecordParser::kTimeProbeRows) +
                " rows, so it was read as time; --column 0 reads it as data)";
      }
      return false;
    };
    const auto accept_row = [&](const TextRow& row) {
      if (info_->samples + info_->dropped_nonfinite + nonfinite_.count() == 0) {
        // First data row: the columns are known, so a missing rate fails before the long read.
        if (!row.has_time && !o_.rate_hz) {
          stop_is_usage = true;
          stop = "no time column (" + TimeColumnList() + ") in the " +
                 (parser_ptr->has_header()
                      ? "header"
                      : "file (it has no header row, and its first column does not increase)") +
                 ": give the sample rate with --rate HZ";
          return false;
        }
        if (several ? !ResolveColumnUnits(*parser_ptr, &units_error)
                    : !ResolveTextUnits(*parser_ptr, &units_error)) {
          return false;
        }
      }
      bool values_finite = true;
      for (double v : row.values) values_finite &= std::isfinite(v);
      if (row.has_time && o_.drop_nonfinite && (!std::isfinite(row.time) || !values_finite)) {
        ++info_->dropped_nonfinite;
        return true;
      }
      if (row.has_time) {
        if (time_unit_s_ == 0.0) {
          const TimeColumnName* name = parser_ptr->time_column_name();
          time_unit_s_ = o_.time_unit_s.value_or(name->seconds_per_unit);
          unit_is_guess_ = !o_.time_unit_s && !name->unit_in_name;
        }
        if (!steps_.Add(row.time * time_unit_s_, row.line, &stop)) return step_refused();
      }
      if (several) {
        AcceptRow(row.values, row.line);
      } else {
        Accept(row.value, row.line);
      }
      return true;
    };
    // A run of common rows: after the first row's checks, and when every value is finite (nothing
    // to drop or list), accept_row's checks made for the whole run at once; else row by row.
    const auto accept_rows = [&](const TextRowBlock& block) {
      const auto row_at = [&](std::size_t k) {
        TextRow row;
        row.line = block.first_line + static_cast<std::int64_t>(k);
        row.values = block.values.subspan(k * block.width, block.width);
        row.value = row.values.front();
        row.has_time = block.has_time;
        if (block.has_time) row.time = block.times[k];
        return row;
      };
      std::size_t first = 0;
      for (; first < block.rows &&
             info_->samples + info_->dropped_nonfinite + nonfinite_.count() == 0;
           ++first) {
        if (!accept_row(row_at(first))) return false;
      }
      const std::span<const double> values = block.values.subspan(first * block.width);
      if (!AllFinite(values) ||
          (block.has_time && (time_unit_s_ == 0.0 || !AllFinite(block.times)))) {
        for (std::size_t k = first; k < block.rows; ++k) {
          if (!accept_row(row_at(k))) return false;
        }
        return true;
      }
      // The rows kept: those before a time step refused, as row by row.
      std::size_t end = block.rows;
      for (std::size_t k = first; block.has_time && k < block.rows; ++k) {
        if (!steps_.Add(block.times[k] * time_unit_s_,
                        block.first_line + static_cast<std::int64_t>(k), &stop)) {
          end = k;
          break;
        }
      }
      const std::int64_t first_line = block.first_line + static_cast<std::int64_t>(first);
      if (!several) {
        AcceptBlock(values.first(end - first), first_line);
      } else {
        for (std::size_t k = 0; k < end - first; ++k) {
          AcceptRow(values.subspan(k * block.width, block.width),
                    first_line + static_cast<std::int64_t>(k));
        }
      }
      return end == block.rows || step_refused();
    };
    TextRecordParser parser(several ? o_.columns : std::vector<std::string>{o_.column}, chooser,
                            accept_row);
    parser.PassRunsAsBlocks(accept_rows);
    parser_ptr = &parser;
    // A plain file's rows are read in two threads when a second core is there; a compressed one's
    // are not, since its decoder already runs beside this thread (OpenSource) and sets the pace.
    const bool two_threads = source->compression() == Compression::kNone && PieceSharing::Useful();
    if (two_threads) parser.UseTwoThreads();
    const std::size_t chunk_bytes = two_threads ? kTwoThreadChunkBytes : kChunkBytes;
    const auto chunk = std::make_unique_for_overwrite<char[]>(chunk_bytes);
    std::string why;
    while (true) {
      // Whole chunks, which the parser can cut for its helper (a pipe or a decoder gives less at
      // a time). Bytes before a read error are parsed first, as when each read was parsed.
      std::size_t got = 0;
      bool read_ok = true;
      bool at_end = false;
      while (got < chunk_bytes && read_ok && !at_end) {
        std::size_t more = 0;
        read_ok = source->Read({chunk.get() + got, chunk_bytes - got}, &more, &why);
        at_end = read_ok && more == 0;
        if (read_ok) got += more;
      }
      const bool ok = (got == 0 || parser.Feed({chunk.get(), got})) && (!at_end || parser.Finish());
      if (ok && !read_ok) return Runtime(error, why);
      if (!ok) {
        if (!units_error.message.empty()) {
          *error = units_error;
          return false;
        }
        if (parser.error().empty()) {
          return stop_is_usage ? Usage(error, In() + stop) : Runtime(error, In() + stop);
        }
        return parser.error_is_usage() ? Usage(error, In() + parser.error())
                                       : Runtime(error, In() + parser.error());
      }
      if (at_end) break;
    }
    info_->has_header = parser.has_header();
    info_->lines = parser.lines();
    info_->column = parser.value_column();
    if (several) {
      for (std::size_t k = 0; k < info_->columns.size(); ++k) {
        info_->columns[k].longest_constant_stretch = stretches_[k].longest();
      }
      if (!info_->columns.empty()) info_->longest_constant_stretch = stretches_.front().longest();
    } else {
      info_->longest_constant_stretch = stretch_.longest();
    }
    info_->time_column = parser.time_column() + bag_stamps_;
    info_->time_column_guessed = parser.time_column_guessed();
    if (time_unit_s_ > 0.0) info_->time_unit_s = time_unit_s_;
    if (parser.data_rows() == 0) {
      return Runtime(error, In() + "no data rows (" + std::to_string(parser.lines()) +
                                " line(s) of comments, blank lines or header)");
    }
    if (nonfinite_.count() > 0) {
      std::string columns;
      for (const std::string& c : parser.value_columns()) columns += (columns.empty() ? "" : ", ") + c;
      return Runtime(error, In() + nonfinite_.Describe((several ? "columns " : "column ") + columns, "line(s)"));
    }
    return true;
  }

  // A block of raw values whose first has index `first`.
  void AcceptBlock(std::span<const double> values, std::int64_t first) {
    if (AllFinite(values) && block_sink_ != nullptr && nonfinite_.count() == 0) {
      info_->samples += static_cast<std::int64_t>(values.size());
      stretch_.AddBlock(values);
      info_->longest_constant_stretch = stretch_.longest();
      (*block_sink_)(values);
      return;
    }
    for (std::size_t k = 0; k < values.size(); ++k) Accept(values[k], first + static_cast<std::int64_t>(k));
  }

  // Maps a raw float64 file that can be used where it lies: a regular file, not compressed (the
  // magic bytes OpenByteSource goes by), not a bag, whole samples only, every value kept (no
  // --drop-nonfinite, which would leave gaps). Anything else is read as a stream.
  bool MapRaw() {
    static_assert(std::endian::native == std::endian::little, "raw samples are little-endian");
    if (format_ != RecordFormat::kFloat64 || o_.drop_nonfinite || o_.path == "-") return false;
    if (!map_->Map(o_.path) || DetectBag(o_.path)) return false;
    const std::span<const char> bytes = map_->bytes();
    static constexpr unsigned char kGzipMagic[] = {0x1f, 0x8b};
    static constexpr unsigned char kXzMagic[] = {0xfd, '7', 'z', 'X', 'Z', 0x00};
    const auto starts_with = [&](const unsigned char* magic, std::size_t n) {
      return bytes.size() >= n && std::memcmp(bytes.data(), magic, n) == 0;
    };
    if (bytes.size() % sizeof(double) != 0 || starts_with(kGzipMagic, sizeof kGzipMagic) ||
        starts_with(kXzMagic, sizeof kXzMagic)) {
      return false;
    }
    *mapped_values_ = {reinterpret_cast<const double*>(bytes.data()), bytes.size() / sizeof(double)};
    return true;
  }

  // The mapped values checked block by block as ReadRaw checks them (the sink, when there is one,
  // sees them in place).
  bool ReadMapped(RecordError* error) {
    const std::span<const double> values = *mapped_values_;
    for (std::size_t first = 0; first < values.size(); first += kBlockValues) {
      AcceptBlock(values.subspan(first, std::min(kBlockValues, values.size() - first)),
                  static_cast<std::int64_t>(first));
    }
    info_->longest_constant_stretch = stretch_.longest();
    if (nonfinite_.count() > 0) {
      return Runtime(error, In() + nonfinite_.Describe("the samples", "0-based index(es)"));
    }
    return true;
  }

  bool ReadRaw(ByteSource* source, RecordError* error) {
    const RawSampleType type =
        format_ == RecordFormat::kFloat32 ? RawSampleType::kFloat32 : RawSampleType::kFloat64;
    RawSampleDecoder decoder(
        type,
        [&](std::span<const double> values, std::int64_t first) {
          AcceptBlock(values, first);
          return true;
        },
        kRawStreamBlockValues);
    info_->column = type == RawSampleType::kFloat32 ? "float32 samples" : "float64 samples";
    // Storage of doubles, so that whole float64 samples read into it are passed on as they lie.
    std::vector<double> chunk(kChunkBytes / sizeof(double));
    const std::span<char> bytes(reinterpret_cast<char*>(chunk.data()), kChunkBytes);
    std::string why;
    while (true) {
      // Whole chunks (a source may return less: the bytes its format check buffered, a pipe's),
      // so that each block but the last is kRawStreamBlockValues values.
      std::size_t got = 0;
      while (got < bytes.size()) {
        std::size_t more = 0;
        if (!source->Read(bytes.subspan(got), &more, &why)) return Runtime(error, why);
        if (more == 0) break;
        got += more;
      }
      if (got == 0) break;
      if (got % sizeof(double) == 0) {
        decoder.FeedStorage({chunk.data(), got / sizeof(double)});
      } else {
        decoder.Feed(bytes.first(got));
      }
    }
    if (!decoder.Finish(&why)) return Runtime(error, In() + why);
    info_->longest_constant_stretch = stretch_.longest();
    if (nonfinite_.count() > 0) {
      return Runtime(error, In() + nonfinite_.Describe("the samples", "0-based index(es)"));
    }
    return true;
  }

  bool Conclude(RecordError* error) {
    if (!info_->time_column.empty()) {
      info_->time = steps_.Summarize();
      const TimeSteps::Summary& t = info_->time;
      if (t.nominal_step_s > kLongestPlausibleStepS && unit_is_guess_) {
        return Usage(error, In() + TimeColumnPhrase() + " steps by " +
                                ShortestDecimal(t.nominal_step_s) +
                                " (as seconds: implausible for a gyro record; it looks like "
                                "ms, us or ns): give --time-units ms|us|ns, or s to confirm");
      }
      if (t.nominal_step_s > 0) {
        const double from_time = RoundToSignificantDigits(1.0 / t.nominal_step_s, 10);
        info_->sample_clock = SampleClock::FromRateHz(from_time);
        info_->rate_source = TimeColumnPhrase() + TimeUnitNote();
        if (o_.rate_hz) {
          if (std::abs(*o_.rate_hz - from_time) > kRateTolerance * from_time &&
              info_->time_column_guessed) {
            // Only a guess (a counter, or time in another unit): the rate given wins.
            info_->sample_clock = SampleClock::FromRateHz(*o_.rate_hz);
            info_->rate_source = "--rate (the headerless first column, read as time, gives " +
                                 ShortestDecimal(from_time) + " Hz: not used)";
            info_->time = TimeSteps::Summary();
            info_->time_column.clear();
            info_->time_column_guessed = false;
            return ConcludeCounts(error);
          }
          if (std::abs(*o_.rate_hz - from_time) > kRateTolerance * from_time) {
            return Usage(error, In() + "--rate " + ShortestDecimal(*o_.rate_hz) +
                                    " Hz disagrees with the " + TimeColumnPhrase() +
                                    " (" + ShortestDecimal(from_time) + " Hz from its step of " +
                                    ShortestDecimal(t.nominal_step_s) +
                                    " s); drop --rate or fix it");
          }
          info_->sample_clock = SampleClock::FromRateHz(*o_.rate_hz);
          info_->rate_source = "--rate (" + TimeColumnPhrase() + " agrees)";
        }
      }
    }
    if (info_->rate_source.empty() && !o_.rate_hz && sidecar_ && sidecar_->sample_rate_hz) {
      info_->sample_clock = SampleClock::FromRateHz(*sidecar_->sample_rate_hz);
      info_->rate_source = "the sidecar " + sidecar_->path;
    } else if (info_->rate_source.empty() && o_.rate_hz && sidecar_ && sidecar_->sample_rate_hz) {
      info_->sample_clock = SampleClock::FromRateHz(*o_.rate_hz);
      info_->rate_source = "--rate (the sidecar " + sidecar_->path + " agrees)";
    }
    return ConcludeCounts(error);
  }

  // The sample counts: the sidecar's and the minimum.
  bool ConcludeCounts(RecordError* error) {
    if (sidecar_ && sidecar_->num_samples) {
      const std::int64_t read = info_->samples + info_->dropped_nonfinite;
      if (read != *sidecar_->num_samples) {
        return Runtime(error, In() + std::to_string(read) + " samples, but the sidecar " +
                                  sidecar_->path + " says " +
                                  std::to_string(*sidecar_->num_samples) +
                                  ": a truncated file or another record's sidecar");
      }
    }
    if (info_->rate_source.empty()) {  // no time column, sidecar or --rate has set the clock
      if (!o_.rate_hz) {
        // A time column with fewer than two samples: it cannot give a rate.
        return Usage(error, In() + "cannot read a sample rate from " +
                                std::to_string(info_->samples) +
                                " sample(s); give it with --rate HZ");
      }
      info_->sample_clock = SampleClock::FromRateHz(*o_.rate_hz);
      info_->rate_source = "--rate";
    }
    if (info_->samples < o_.min_samples) {
      return Runtime(error, In() + "only " + std::to_string(info_->samples) + " sample(s)" +
                                (info_->dropped_nonfinite
                                     ? " after dropping " +
                                           std::to_string(info_->dropped_nonfinite) + " non-finite"
                                     : std::string()) +
                                " in " + info_->column + "; at least " +
                                std::to_string(o_.min_samples) + " are needed");
    }
    return true;
  }

  std::string TimeColumnPhrase() const {
    return TextRecordParser::TimeColumnPhrase(info_->time_column);
  }

  // " in ns" when the time column is not in seconds.
  std::string TimeUnitNote() const {
    static constexpr std::pair<double, std::string_view> kNames[] = {
        {1e-3, "ms"}, {1e-6, "us"}, {1e-9, "ns"}};
    for (const auto& [seconds, name] : kNames) {
      if (info_->time_unit_s == seconds) return " in " + std::string(name);
    }
    return "";
  }

  static std::string TimeColumnList() {
    std::string out;
    for (const TimeColumnName& name : kTimeColumnNames) {
      if (name.seconds_per_unit == 1.0 && name.name != "timestamp_s")
        out += (out.empty() ? "" : ", ") + std::string(name.name);
    }
    return out + ", or with a unit: t_ms, time_us, timestamp_ns, %time ...";
  }

  // A bare-named time column (t, time, timestamp) is read as seconds; a step longer than this
  // means it is not (a 100 Hz record with ms, us or ns stamps).
  static constexpr double kLongestPlausibleStepS = 10.0;

  static inline const std::function<void(double)> kNoSink = [](double) {};
  static inline const std::function<void(std::span<const double>)> kNoBlockSink = [](std::span<const double>) {};
  const RecordReaderOptions& o_;
  const std::function<void(double)>& sink_;
  const std::function<void(std::span<const double>)>* block_sink_;
  const std::function<void(std::span<const double>)>* row_sink_ = nullptr;
  std::vector<ConstantStretchTracker> stretches_;  // several columns: one per column
  double time_unit_s_ = 0.0;  // set at the first row with a time
  bool unit_is_guess_ = false;
  RecordInfo* info_;
  std::optional<RawSidecar> sidecar_;
  RecordFormat format_ = RecordFormat::kText;  // o_.format, or the sidecar's dtype
  NonFiniteLog nonfinite_;
  TimeSteps steps_;
  std::string bag_stamps_;  // a ROS bag: where its time column comes from
  ConstantStretchTracker stretch_;
  MappedFile* map_ = nullptr;
  std::span<const double>* mapped_values_ = nullptr;
  bool not_mapped_ = false;
  bool defer_checks_ = false;
};

}  // namespace

bool ParseRecordFormat(std::string_view text, RecordFormat* format, std::string* why) {
  for (RecordFormat f : {RecordFormat::kText, RecordFormat::kFloat32, RecordFormat::kFloat64}) {
    if (text == RecordFormatName(f)) {
      *format = f;
      return true;
    }
  }
  if (why) *why = "unknown format '" + std::string(text) + "' (expected text, f32 or f64)";
  return false;
}

std::string_view RecordFormatName(RecordFormat format) {
  switch (format) {
    case RecordFormat::kText:
      return "text";
    case RecordFormat::kFloat32:
      return "f32";
    case RecordFormat::kFloat64:
      return "f64";
  }
  return "?";
}

bool ReadRecord(const RecordReaderOptions& options, const std::function<void(double)>& sink,
                RecordInfo* info, RecordError* error, const BlockSink* block_sink) {
  return Reader(options, sink, info, block_sink).Run(error);
}

namespace {

// A text file's row count from the newlines in its first 64 KiB, 5 % over (rows vary in width);
// 0 when that sample has too few lines to say. A compressed file or a bag gives a low count
// (its bytes are not rows), which only leaves push_back to grow the vector as before.
std::size_t EstimatedTextRows(const std::string& path, std::uintmax_t bytes) {
  static constexpr std::size_t kSampleBytes = 1 << 16;
  if (path == "-") return 0;
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) return 0;
  std::vector<char> sample(kSampleBytes);
  const std::size_t got = std::fread(sample.data(), 1, sample.size(), file);
  std::fclose(file);
  // Lines that start with '#' (a preamble of comments) are not rows.
  std::ptrdiff_t lines = 0;
  for (std::size_t i = 0; i + 1 < got; ++i) lines += sample[i] == '\n' && sample[i + 1] != '#';
  if (lines < 16) return 0;
  const double per_byte = static_cast<double>(lines) / static_cast<double>(got);
  return static_cast<std::size_t>(1.05 * per_byte * static_cast<double>(bytes));
}

}  // namespace

bool ReadRecordValues(const RecordReaderOptions& options, std::vector<double>* values,
                      RecordInfo* info, RecordError* error, std::size_t leading_zeros) {
  values->clear();
  // A raw record's size tells the sample count (exactly when uncompressed, a lower bound when
  // compressed): reserving it spares the growth copies and page faults of push_back, which cost
  // more than the Allan pass itself on 1e8-sample files.
  const std::size_t width = options.format == RecordFormat::kFloat64   ? 8
                            : options.format == RecordFormat::kFloat32 ? 4
                                                                      : 0;
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(options.path, ec);
  if (width > 0 && !ec) values->reserve(leading_zeros + static_cast<std::size_t>(bytes) / width);
  if (width == 0 && !ec) {
    try {
      values->reserve(leading_zeros + EstimatedTextRows(options.path, bytes));
    } catch (const std::exception&) {  // an estimate too large to reserve: grow as rows come
    }
  }
  AdviseHugePages(values->data(), values->capacity() * sizeof(double));
  values->assign(leading_zeros, 0.0);
  const std::function<void(double)> sink = [values](double v) { values->push_back(v); };
  const std::function<void(std::span<const double>)> block_sink =
      [values](std::span<const double> block) {
        values->insert(values->end(), block.begin(), block.end());
      };
  return Reader(options, sink, info, &block_sink).Run(error);
}

MapOutcome MapRecordValues(const RecordReaderOptions& options, MappedFile* map, std::span<const double>* values,
                           RecordInfo* info, RecordError* error, const BlockSink* checked_blocks) {
  Reader reader(options, map, values, info, checked_blocks);
  if (reader.Run(error)) return MapOutcome::kMapped;
  return reader.not_mapped() ? MapOutcome::kNotMapped : MapOutcome::kFailed;
}

MapOutcome MapRecordValuesUnchecked(const RecordReaderOptions& options, MappedFile* map,
                                    std::span<const double>* values, RecordInfo* info, RecordError* error,
                                    MappedRecordChecks* checks) {
  // The reader outlives this call in *checks, with its own copy of the options it refers to.
  struct Unchecked {
    Unchecked(const RecordReaderOptions& o, MappedFile* map, std::span<const double>* values, RecordInfo* info)
        : options(o), reader(options, map, values, info, nullptr) {}
    RecordReaderOptions options;
    Reader reader;
  };
  const auto unchecked = std::make_shared<Unchecked>(options, map, values, info);
  unchecked->reader.DeferChecks();
  if (unchecked->reader.Run(error)) {
    *checks = [unchecked](const BlockSink* checked_blocks, RecordError* check_error) {
      return unchecked->reader.CheckMapped(checked_blocks, check_error);
    };
    return MapOutcome::kMapped;
  }
  return unchecked->reader.not_mapped() ? MapOutcome::kNotMapped : MapOutcome::kFailed;
}

bool ReadRecordColumns(const RecordReaderOptions& options, std::vector<std::vector<double>>* values,
                       RecordInfo* info, RecordError* error) {
  values->clear();
  const std::function<void(std::span<const double>)> row_sink = [values](std::span<const double> row) {
    if (values->size() != row.size()) values->resize(row.size());
    for (std::size_t k = 0; k < row.size(); ++k) (*values)[k].push_back(row[k]);
  };
  if (!ReadRecordRows(options, row_sink, info, error)) return false;
  values->resize(info->columns.size());
  return true;
}

bool ReadRecordRows(const RecordReaderOptions& options, const std::function<void(std::span<const double>)>& row_sink,
                    RecordInfo* info, RecordError* error) {
  return Reader(options, &row_sink, info).Run(error);
}

}  // namespace allanlab::app
