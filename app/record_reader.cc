#include "app/record_reader.h"

#include <filesystem>
#include <system_error>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "app/provenance.h"
#include "app/raw_sample_decoder.h"
#include "app/subcommand.h"
#include "app/text_record_parser.h"

namespace allanlab::app {
namespace {

constexpr std::size_t kChunkBytes = 1 << 18;
constexpr std::size_t kBlockValues = 4096;  // raw values decoded per block

// The mean of a million printed steps carries its rounding in the last digits (100 Hz from
// t = 0.00, 0.01, ... comes out as 99.99999999999993 Hz); ten digits are more than a time column
// can resolve and less than its noise.
double RoundToSignificantDigits(double value, int digits) {
  char text[40];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return std::strtod(text, nullptr);
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

  bool Run(RecordError* error) {
    *info_ = RecordInfo();
    info_->path = o_.path;
    info_->format = o_.format;
    std::string why;
    if (o_.format != RecordFormat::kText && !o_.rate_hz) {
      return Usage(error, "raw " + std::string(RecordFormatName(o_.format)) +
                              " samples carry no time: give the sample rate with --rate HZ");
    }
    std::unique_ptr<ByteSource> source;
    if (!OpenByteSource(o_.path, &source, &why)) return Runtime(error, why);
    info_->compression = source->compression();
    const bool ok = o_.format == RecordFormat::kText ? ReadText(source.get(), error)
                                                     : ReadRaw(source.get(), error);
    if (!ok) return false;
    return Conclude(error);
  }

 private:
  bool Usage(RecordError* error, const std::string& message) {
    *error = {kExitUsageError, message};
    return false;
  }
  bool Runtime(RecordError* error, const std::string& message) {
    *error = {kExitRuntimeError, message};
    return false;
  }
  std::string In() const { return o_.path + ": "; }

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
    stretch_.Add(value);
    info_->longest_constant_stretch = stretch_.longest();
    if (nonfinite_.count() == 0) sink_(value);
  }

  bool ReadText(ByteSource* source, RecordError* error) {
    std::string stop;  // why the sink stopped the parser
    bool stop_is_usage = false;
    TextRecordParser* parser_ptr = nullptr;
    TextRecordParser parser(o_.column, [&](const TextRow& row) {
      if (info_->samples + info_->dropped_nonfinite + nonfinite_.count() == 0) {
        // First data row: the columns are known, so a missing rate fails before the long read.
        if (!row.has_time && !o_.rate_hz) {
          stop_is_usage = true;
          stop = "no time column (" + TimeColumnList() + ") in the " +
                 (parser_ptr->has_header() ? "header" : "file (it has no header row)") +
                 ": give the sample rate with --rate HZ";
          return false;
        }
      }
      if (row.has_time && o_.drop_nonfinite &&
          (!std::isfinite(row.time) || !std::isfinite(row.value))) {
        ++info_->dropped_nonfinite;
        return true;
      }
      if (row.has_time) {
        if (time_unit_s_ == 0.0) {
          const TimeColumnName* name = parser_ptr->time_column_name();
          time_unit_s_ = o_.time_unit_s.value_or(name->seconds_per_unit);
          unit_is_guess_ = !o_.time_unit_s && !name->unit_in_name;
        }
        if (!steps_.Add(row.time * time_unit_s_, row.line, &stop)) return false;
      }
      Accept(row.value, row.line);
      return true;
    });
    parser_ptr = &parser;
    std::vector<char> chunk(kChunkBytes);
    std::string why;
    while (true) {
      std::size_t got = 0;
      if (!source->Read(chunk, &got, &why)) return Runtime(error, why);
      const bool ok = got == 0 ? parser.Finish() : parser.Feed({chunk.data(), got});
      if (!ok) {
        if (parser.error().empty()) {
          return stop_is_usage ? Usage(error, In() + stop) : Runtime(error, In() + stop);
        }
        return parser.error_is_usage() ? Usage(error, In() + parser.error())
                                       : Runtime(error, In() + parser.error());
      }
      if (got == 0) break;
    }
    info_->has_header = parser.has_header();
    info_->lines = parser.lines();
    info_->column = parser.value_column();
    info_->time_column = parser.time_column();
    if (time_unit_s_ > 0.0) info_->time_unit_s = time_unit_s_;
    if (parser.data_rows() == 0) {
      return Runtime(error, In() + "no data rows (" + std::to_string(parser.lines()) +
                                " line(s) of comments, blank lines or header)");
    }
    if (nonfinite_.count() > 0) {
      return Runtime(error, In() + nonfinite_.Describe("column " + info_->column, "line(s)"));
    }
    return true;
  }

  bool ReadRaw(ByteSource* source, RecordError* error) {
    const RawSampleType type =
        o_.format == RecordFormat::kFloat32 ? RawSampleType::kFloat32 : RawSampleType::kFloat64;
    RawSampleDecoder decoder(
        type,
        [&](std::span<const double> values, std::int64_t first) {
          bool finite = true;
          for (double v : values) finite &= std::isfinite(v);
          if (finite && block_sink_ != nullptr && nonfinite_.count() == 0) {
            info_->samples += static_cast<std::int64_t>(values.size());
            for (double v : values) stretch_.Add(v);
            info_->longest_constant_stretch = stretch_.longest();
            (*block_sink_)(values);
            return true;
          }
          for (std::size_t k = 0; k < values.size(); ++k) {
            Accept(values[k], first + static_cast<std::int64_t>(k));
          }
          return true;
        },
        kBlockValues);
    info_->column = type == RawSampleType::kFloat32 ? "float32 samples" : "float64 samples";
    std::vector<char> chunk(kChunkBytes);
    std::string why;
    while (true) {
      std::size_t got = 0;
      if (!source->Read(chunk, &got, &why)) return Runtime(error, why);
      if (got == 0) break;
      decoder.Feed({chunk.data(), got});
    }
    if (!decoder.Finish(&why)) return Runtime(error, In() + why);
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
        return Usage(error, In() + "time column " + info_->time_column + " steps by " +
                                ShortestDecimal(t.nominal_step_s) +
                                " (as seconds: implausible for a gyro record; it looks like "
                                "ms, us or ns): give --time-units ms|us|ns, or s to confirm");
      }
      if (t.nominal_step_s > 0) {
        const double from_time = RoundToSignificantDigits(1.0 / t.nominal_step_s, 10);
        info_->sample_rate_hz = from_time;
        info_->rate_source = "time column " + info_->time_column + TimeUnitNote();
        if (o_.rate_hz) {
          if (std::abs(*o_.rate_hz - from_time) > kRateTolerance * from_time) {
            return Usage(error, In() + "--rate " + ShortestDecimal(*o_.rate_hz) +
                                    " Hz disagrees with the time column " + info_->time_column +
                                    " (" + ShortestDecimal(from_time) + " Hz from its step of " +
                                    ShortestDecimal(t.nominal_step_s) +
                                    " s); drop --rate or fix it");
          }
          info_->sample_rate_hz = *o_.rate_hz;
          info_->rate_source = "--rate (time column " + info_->time_column + " agrees)";
        }
      }
    }
    if (info_->sample_rate_hz == 0.0) {
      if (!o_.rate_hz) {
        // A time column with fewer than two samples: it cannot give a rate.
        return Usage(error, In() + "cannot read a sample rate from " +
                                std::to_string(info_->samples) +
                                " sample(s); give it with --rate HZ");
      }
      info_->sample_rate_hz = *o_.rate_hz;
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

  const RecordReaderOptions& o_;
  const std::function<void(double)>& sink_;
  const std::function<void(std::span<const double>)>* block_sink_;
  double time_unit_s_ = 0.0;  // set at the first row with a time
  bool unit_is_guess_ = false;
  RecordInfo* info_;
  NonFiniteLog nonfinite_;
  TimeSteps steps_;
  ConstantStretchTracker stretch_;
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
                RecordInfo* info, RecordError* error) {
  return Reader(options, sink, info).Run(error);
}

bool ReadRecordValues(const RecordReaderOptions& options, std::vector<double>* values,
                      RecordInfo* info, RecordError* error) {
  values->clear();
  // A raw record's size tells the sample count (exactly when uncompressed, a lower bound when
  // compressed): reserving it spares the growth copies and page faults of push_back, which cost
  // more than the Allan pass itself on 1e8-sample files.
  const std::size_t width = options.format == RecordFormat::kFloat64   ? 8
                            : options.format == RecordFormat::kFloat32 ? 4
                                                                      : 0;
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(options.path, ec);
  // One spare slot: ComputeAvarInPlace integrates N samples into N + 1 values.
  if (width > 0 && !ec) values->reserve(static_cast<std::size_t>(bytes) / width + 1);
  const std::function<void(double)> sink = [values](double v) { values->push_back(v); };
  const std::function<void(std::span<const double>)> block_sink =
      [values](std::span<const double> block) {
        values->insert(values->end(), block.begin(), block.end());
      };
  return Reader(options, sink, info, &block_sink).Run(error);
}

}  // namespace allanlab::app
