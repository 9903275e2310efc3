#include "app/input/record_curve.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <thread>
#include <span>
#include <utility>
#include <vector>

#include "app/input/accel_units.h"
#include "app/input/constant_stretch.h"
#include "app/input/imu_columns.h"
#include "app/input/mapped_file.h"
#include "common/huge_pages.h"
#include "common/piece_sharing.h"
#include "app/input/rate_units.h"
#include "app/input/record_reader.h"
#include "app/input/stated_units.h"
#include "app/reports/avar_report.h"
#include "common/number_text.h"
#include "estimators/allan_family.h"
#include "estimators/avar.h"
#include "estimators/confidence.h"
#include "estimators/phase_checkpoints.h"
#include "estimators/phase_integral.h"
#include "estimators/streaming_avar.h"
#include "sim/units.h"

namespace allanlab::app {
namespace {

using estimators::ConfidenceMethod;
using estimators::InputKind;
using estimators::Statistic;

using Failure = CommandFailure;
Failure Usage(std::string message) { return UsageFailure(std::move(message)); }
Failure Runtime(std::string message) { return RuntimeFailure(std::move(message)); }

void PrintWarning(const std::string& message, const std::string& command) {
  std::cerr << "allanlab " << command << ": warning: " << message << std::endl;
}

bool PositiveFinite(double v) { return std::isfinite(v) && v > 0.0; }

// The options turned into typed choices.
struct Plan {
  RecordReaderOptions read;
  InputKind input = InputKind::kRate;
  RateUnit output_unit = RateUnit::kDegPerHour;
  AccelUnit accel_output_unit = AccelUnit::kMilliG;
  estimators::AvarOptions avar;
};

std::optional<Failure> MakePlan(const RecordCurveOptions& o, Plan* plan) {
  std::string why;
  if (o.path.empty()) return Usage("FILE is required");
  plan->read.path = o.path;
  plan->read.column = o.column;
  plan->read.topic = o.topic;
  if (SeveralColumns(o)) {
    if (!o.columns.empty() && o.column.find(',') == std::string::npos && !o.column.empty()) {
      return Usage("--column and --columns: give one of them");
    }
    if (o.imu && (!o.columns.empty() || !o.column.empty())) {
      return Usage("--imu takes every gyro and accelerometer column: drop --column/--columns, or "
                   "drop --imu to name them");
    }
    const std::string list = o.columns.empty() ? o.column : o.columns;
    if (!o.imu && !ParseColumnList(list, &plan->read.columns, &why)) return Usage("--columns: " + why);
    plan->read.column.clear();
    plan->read.imu = o.imu;
  }
  if (!o.accel_units.empty()) {
    AccelUnit unit;
    if (!ParseAccelUnit(o.accel_units, &unit, &why)) return Usage("--accel-units: " + why);
    plan->read.accel_units = std::string(AccelUnitName(unit));
  }
  if (!ParseAccelUnit(o.accel_out_units, &plan->accel_output_unit, &why)) {
    return Usage("--accel-out-units: " + why);
  }
  plan->read.drop_nonfinite = o.drop_nonfinite;
  if (o.format.empty()) {
    plan->read.format_from_sidecar = true;
  } else if (!ParseRecordFormat(o.format, &plan->read.format, &why)) {
    return Usage("--format: " + why);
  }
  if (plan->read.format != RecordFormat::kText && (!o.column.empty() || SeveralColumns(o))) {
    return Usage("--column applies to text records; raw " + o.format + " has one column");
  }
  if (o.rate_hz) {
    if (!PositiveFinite(*o.rate_hz)) {
      return Usage("--rate must be a finite number of Hz > 0, got " + ShortestDecimal(*o.rate_hz));
    }
    plan->read.rate_hz = o.rate_hz;
  }
  if (!o.time_units.empty()) {
    static constexpr std::pair<std::string_view, double> kTimeUnits[] = {
        {"s", 1.0}, {"ms", 1e-3}, {"us", 1e-6}, {"ns", 1e-9}};
    for (const auto& [name, seconds] : kTimeUnits) {
      if (o.time_units == name) plan->read.time_unit_s = seconds;
    }
    if (!plan->read.time_unit_s) {
      return Usage("--time-units must be s, ms, us or ns, got '" + o.time_units + "'");
    }
    if (plan->read.format != RecordFormat::kText) {
      return Usage("--time-units applies to a text record's time column; raw " + o.format +
                   " has none");
    }
  }
  if (o.type == "rate") {
    plan->input = InputKind::kRate;
  } else if (o.type == "angle") {
    plan->input = InputKind::kAngle;
    // One more angle than rates: 3 rates need 4 angles.
    plan->read.min_samples = 4;
  } else {
    return Usage("--type: unknown '" + o.type + "' (expected rate or angle)");
  }
  plan->read.kind = plan->input;
  // The record's own statement of its units is read with the file (app/input/stated_units.h).
  if (!o.units.empty() && !CanonicalUnit(o.units, plan->input, &plan->read.units, &why)) {
    return Usage("--units: " + why);
  }
  if (!ParseRateUnit(o.out_units, &plan->output_unit, &why)) return Usage("--out-units: " + why);

  estimators::AvarOptions& a = plan->avar;
  a.input = plan->input;
  if (!estimators::ParseStatistic(o.estimator, &a.statistic)) {
    return Usage("--estimator: unknown '" + o.estimator +
                 "' (expected overlapping, nonoverlapping, modified, hadamard, "
                 "hadamard_nonoverlapping, total or time)");
  }
  if (!estimators::TauGridOptions::Parse(o.taus, &a.taus, &why)) return Usage("--taus: " + why);
  const std::string ci = o.ci.value_or(o.stream ? "simple" : "auto");
  if (ci == "auto") {
    a.confidence_method = ConfidenceMethod::kAuto;
  } else if (ci == "gr") {
    a.confidence_method = ConfidenceMethod::kGreenhallRiley;
  } else if (ci == "simple") {
    a.confidence_method = ConfidenceMethod::kSimple;
  } else if (ci == "none") {
    a.confidence_method = ConfidenceMethod::kNone;
  } else {
    return Usage("--ci: unknown '" + ci + "' (expected auto, gr, simple or none)");
  }
  if (!(o.confidence > 0.0 && o.confidence < 1.0)) {
    return Usage("--confidence must be in (0, 1), got " + ShortestDecimal(o.confidence));
  }
  a.confidence = o.confidence;
  a.identification_max_averages = o.identification_max_averages;
  if (o.stream) {
    if (a.statistic != Statistic::kAllanOverlapping &&
        a.statistic != Statistic::kAllanNonOverlapping) {
      return Usage("--stream computes overlapping or nonoverlapping AVAR only, not " + o.estimator);
    }
    if (a.taus.kind != estimators::TauGridKind::kOctave) {
      return Usage("--stream computes octave taus only (--taus octave), not " + o.taus);
    }
    if (a.confidence_method == ConfidenceMethod::kGreenhallRiley ||
        a.confidence_method == ConfidenceMethod::kAuto) {
      return Usage("--stream cannot give --ci " + ci +
                   ": that EDF needs the record in memory (its differences or the noise type at "
                   "each tau); use --ci simple or none, or drop --stream");
    }
    estimators::StreamingAvarOptions stream{o.stream_exact_max_m};
    if (!stream.IsValid(&why)) return Usage("--stream-exact-m: " + why);
  }
  return std::nullopt;
}

// Samples in the record's units (RecordInfo::units, canonical) to SI: rad/s, or rad for angle
// input, with the sim/units.h arithmetic.
class InputScale {
 public:
  InputScale(InputKind kind, const std::string& unit) : kind_(kind) {
    if (kind == InputKind::kAngle) {
      angle_to_si_ = unit == "deg" ? units::kRadPerDeg : unit == "arcsec" ? units::kRadPerArcsec : 1.0;
    } else {
      std::string ignored;
      ParseRateUnit(unit, &rate_, &ignored);  // canonical: always parses
    }
  }
  // rad/s or rad in: the values are SI as they are.
  bool identity() const {
    return kind_ == InputKind::kAngle ? angle_to_si_ == 1.0 : rate_ == RateUnit::kRadPerSecond;
  }
  double operator()(double v) const {
    return kind_ == InputKind::kAngle ? v * angle_to_si_ : ToRadPerSecond(rate_, v);
  }
  void Apply(std::span<double> values) const {
    if (kind_ == InputKind::kAngle) {
      for (double& v : values) v *= angle_to_si_;
    } else {
      ToRadPerSecond(rate_, values);
    }
  }

 private:
  InputKind kind_;
  RateUnit rate_ = RateUnit::kRadPerSecond;
  double angle_to_si_ = 1.0;
};

// The curve of the values in storage[1..] (storage[0] a spare slot), in the record's units
// (report->record says which, and the sample rate), converted to SI (rad/s or rad) in place.
std::optional<Failure> CurveOfValues(const Plan& plan, std::span<double> storage, AvarReport* report) {
  InputScale(plan.input, report->record.units).Apply(storage.subspan(1));
  report->input_units = report->record.units;
  estimators::AvarOptions options = plan.avar;
  options.sample_clock = report->record.sample_clock;
  // The record is not needed afterwards: its storage becomes the integrated record.
  if (!estimators::ComputeAvarOnStorage(options, storage, &report->summary)) {
    return Runtime(plan.read.path + ": " + report->summary.message);
  }
  return std::nullopt;
}

// The curve of a mapped record (MapRecordValues): rate samples already in SI are used where they
// lie (on long records integrated as the reader checked them: `checkpoints`, complete); others
// are copied behind a spare slot and converted as CurveOfValues converts them.
std::optional<Failure> CurveOfMappedValues(const Plan& plan, std::span<const double> values,
                                           std::optional<estimators::PhaseCheckpoints> checkpoints, AvarReport* report,
                                           std::span<double> phase = {}) {
  if (plan.input == InputKind::kRate && InputScale(plan.input, report->record.units).identity()) {
    report->input_units = report->record.units;
    estimators::AvarOptions options = plan.avar;
    options.sample_clock = report->record.sample_clock;
    const bool ok = checkpoints && checkpoints->complete()
                        ? estimators::ComputeAvarFromCheckpoints(options, std::move(*checkpoints), &report->summary)
                        : estimators::ComputeAvar(options, values, &report->summary, phase);
    if (ok) return std::nullopt;
    // A failure is reported as the copied record's pass reports it (where the running sum overflows).
  }
  std::vector<double> storage(kSpareSlot + values.size());
  std::copy(values.begin(), values.end(), storage.begin() + kSpareSlot);
  return CurveOfValues(plan, storage, report);
}

// The curve of a mapped record (MapRecordValuesUnchecked) once `checks` pass. Rate samples in SI
// from ~1e6 to kCheckpointMinSamples, with a second core: the checks run in a helper thread, which
// first has the kernel fault in the pages of the integrated record, while this thread computes
// the curve (none of it is used unless the checks pass): the two steps that came before the
// Allan pass, on the core that had nothing to do (1e7 samples: ~8 ms of checks and ~8 ms of page
// zeroing). Longer records are integrated block by block as the checks pass them (while they are
// in cache: estimators::kCheckpointMinSamples), which spares a pass over them.
std::optional<Failure> CurveOfMappedRecord(const Plan& plan, std::span<const double> values,
                                           const MappedRecordChecks& checks, AvarReport* report) {
  const bool si_rate = plan.input == InputKind::kRate && InputScale(plan.input, report->record.units).identity();
  // Below ~1e6 samples the checks take well under a millisecond: no thread for them.
  constexpr std::size_t kOverlappedChecksSamples = std::size_t{1} << 20;
  if (si_rate && values.size() >= kOverlappedChecksSamples && values.size() < estimators::kCheckpointMinSamples &&
      PieceSharing::Useful()) {
    const std::size_t size = values.size() + 1;
    const auto phase = std::make_unique_for_overwrite<double[]>(size);
    AdviseHugePages(phase.get(), size * sizeof(double));
    RecordError check_error;
    bool checked = false;
    std::thread helper([&] {
      PopulateForWrite(phase.get(), size * sizeof(double));
      checked = checks(nullptr, &check_error);
    });
    std::optional<Failure> failure = CurveOfMappedValues(plan, values, std::nullopt, report, {phase.get(), size});
    helper.join();
    if (!checked) return Failure{check_error.exit_code, check_error.message};
    return failure;
  }
  std::optional<estimators::PhaseCheckpoints> checkpoints;
  bool integrate = plan.input == InputKind::kRate;
  const BlockSink integrate_blocks = [&](std::span<const double> block) {
    if (!integrate) return;
    if (values.size() < estimators::kCheckpointMinSamples) {
      integrate = false;
      return;
    }
    if (!checkpoints) {
      integrate = si_rate;
      if (!integrate) return;
      checkpoints.emplace(values, estimators::ReferenceLevel(values), estimators::PhaseCheckpoints::Deferred{});
    }
    checkpoints->IntegrateUpTo(block.data() + block.size() - values.data());
  };
  RecordError error;
  if (!checks(&integrate_blocks, &error)) return Failure{error.exit_code, error.message};
  return CurveOfMappedValues(plan, values, std::move(checkpoints), report);
}

// Reads the record and computes its curve in memory.
std::optional<Failure> ComputeInMemory(const Plan& plan, AvarReport* report) {
  RecordError error;
  {
    MappedFile map;
    std::span<const double> values;
    MappedRecordChecks checks;
    switch (MapRecordValuesUnchecked(plan.read, &map, &values, &report->record, &error, &checks)) {
      case MapOutcome::kMapped:
        return CurveOfMappedRecord(plan, values, checks, report);
      case MapOutcome::kFailed:
        return Failure{error.exit_code, error.message};
      case MapOutcome::kNotMapped:
        break;
    }
  }
  std::vector<double> storage;
  if (!ReadRecordValues(plan.read, &storage, &report->record, &error, kSpareSlot)) {
    return Failure{error.exit_code, error.message};
  }
  return CurveOfValues(plan, storage, report);
}

// A record handed over in memory (ComputeCurveFromSamples): described as the reader describes a
// file, after the checks the reader makes (units stated, finite values, enough samples).
std::optional<Failure> DescribeSamples(const RecordCurveOptions& o, const Plan& plan,
                                       const std::vector<double>& values, RecordInfo* info) {
  if (plan.read.units.empty()) {
    return Usage(o.path + ": units are needed (" +
                 std::string(plan.input == InputKind::kAngle ? "deg, rad or arcsec" : "deg/s, deg/h or rad/s") + ")");
  }
  if (!o.rate_hz) return Usage(o.path + ": the sample rate is needed");
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      return Runtime(o.path + ": sample " + std::to_string(i) + " is not finite (" + ShortestDecimal(values[i]) + ")");
    }
  }
  if (static_cast<std::int64_t>(values.size()) < plan.read.min_samples) {
    return Runtime(o.path + ": " + std::to_string(values.size()) + " samples; at least " +
                   std::to_string(plan.read.min_samples) + " are needed");
  }
  info->path = o.path;
  info->column = o.path;
  info->units = plan.read.units;
  info->units_source = "units";
  info->samples = static_cast<std::int64_t>(values.size());
  info->sample_clock = SampleClock::FromRateHz(*o.rate_hz);
  info->rate_source = "rate";
  return std::nullopt;
}

// A single column's values in the record's units to a rate in rad/s (angle input differenced).
void RateToSi(const Plan& plan, const RecordInfo& info, std::vector<double>* values) {
  InputScale(plan.input, info.units).Apply(*values);
  if (plan.input == InputKind::kAngle) *values = estimators::AngleToRate(*values, info.sample_clock.period_s());
}

// One column of a several-column read to SI: a gyro's as InputScale, an accelerometer's to m/s^2.
void ColumnToSi(const Plan& plan, const ColumnInfo& c, std::vector<double>* values) {
  if (c.sensor == ImuSensor::kGyro) {
    InputScale(plan.input, c.units).Apply(*values);
    return;
  }
  AccelUnit unit;
  ParseAccelUnit(c.units, &unit, nullptr);  // canonical: always parses
  AccelToSi(unit, *values);
}

// Column k of a several-column read as the report of a record of its own.
void DescribeColumn(const Plan& plan, const RecordInfo& info, std::size_t k, const std::string& taus_text,
                    AvarReport* r) {
  const ColumnInfo& c = info.columns[k];
  r->record = info;
  r->record.column = c.name;
  r->record.units = c.units;
  r->record.units_source = c.units_source;
  r->record.longest_constant_stretch = c.longest_constant_stretch;
  r->input_units = c.units;
  r->sensor = c.sensor;
  r->output_unit = plan.output_unit;
  r->accel_output_unit = plan.accel_output_unit;
  r->taus_text = taus_text;
}

// Every asked column in SI (rad/s, rad or m/s^2), one report each, from one read of the record.
std::optional<Failure> ComputeColumnsInMemory(const Plan& plan, const std::string& taus_text,
                                              std::vector<AvarReport>* reports) {
  std::vector<std::vector<double>> columns;
  RecordInfo info;
  RecordError error;
  if (!ReadRecordColumns(plan.read, &columns, &info, &error)) {
    return Failure{error.exit_code, error.message};
  }
  reports->assign(columns.size(), AvarReport());
  for (std::size_t k = 0; k < columns.size(); ++k) {
    const ColumnInfo& c = info.columns[k];
    AvarReport& r = (*reports)[k];
    DescribeColumn(plan, info, k, taus_text, &r);
    estimators::AvarOptions options = plan.avar;
    ColumnToSi(plan, c, &columns[k]);
    // Acceleration samples are the rate of velocity.
    if (c.sensor == ImuSensor::kAccelerometer) options.input = InputKind::kRate;
    options.sample_clock = info.sample_clock;
    if (!estimators::ComputeAvarInPlace(options, &columns[k], &r.summary)) {
      return Runtime(plan.read.path + ": column " + c.name + ": " + r.summary.message);
    }
    std::vector<double>().swap(columns[k]);
  }
  return std::nullopt;
}

// A streamed curve's points into the report (tau0 from report->record, known once the file is
// read): values scaled by `scale` (1 / tau0^2 for angle input, whose differences were streamed).
std::optional<Failure> StreamedCurve(const Plan& plan, const estimators::StreamingAvar& stream, bool angle,
                                     std::int64_t exact_max_m, AvarReport* report) {
  const double tau0 = report->record.sample_clock.period_s();
  const double scale = angle ? 1.0 / (tau0 * tau0) : 1.0;
  estimators::AvarSummary& s = report->summary;
  s.options = plan.avar;
  s.options.sample_clock = report->record.sample_clock;
  s.num_samples = stream.count();
  const bool overlapping = plan.avar.statistic == Statistic::kAllanOverlapping;
  for (const estimators::StreamingAvarPoint& p : stream.Points()) {
    estimators::AvarPoint point;
    point.m = p.m;
    point.tau_s = static_cast<double>(p.m) * tau0;
    point.value = (overlapping ? p.overlapping : p.nonoverlapping) * scale;
    point.terms = overlapping ? p.overlapping_terms : p.nonoverlapping_terms;
    if (plan.avar.confidence_method == ConfidenceMethod::kSimple) {
      point.edf = estimators::SimpleEdf(stream.count() / p.m);
      if (point.edf > 0) {
        const estimators::Interval ci =
            estimators::ChiSquareInterval(point.value, point.edf, plan.avar.confidence);
        point.ci_low = ci.low;
        point.ci_high = ci.high;
      }
    }
    s.points.push_back(point);
    report->overlap_stride.push_back(overlapping ? p.overlapping_stride : p.m);
  }
  if (s.points.empty()) {
    return Runtime(plan.read.path + (report->record.columns.size() > 1 ? ": column " + report->record.column : "") +
                   ": " + std::to_string(stream.count()) + " rate samples give no octave tau");
  }
  s.ok = true;
  report->streamed = true;
  report->stream_exact_max_m = exact_max_m;
  return std::nullopt;
}

// One pass in bounded memory: the rate (angle differences for angle input) goes straight from the
// reader into the streaming estimator; units and tau0 are applied to the results at the end,
// since tau0 may only be known from the time column once the file has been read.
std::optional<Failure> ComputeStreamed(const Plan& plan, std::int64_t exact_max_m,
                                       AvarReport* report) {
  estimators::StreamingAvar stream(estimators::StreamingAvarOptions{exact_max_m});
  bool have_previous = false;
  double previous = 0.0;
  const bool angle = plan.input == InputKind::kAngle;
  RecordError error;
  // The units are known once the header is read, before the first value (record_reader.h).
  std::optional<InputScale> scale_to_si;
  // A raw rate record's values come a block at a time: one call per block, not per value.
  std::vector<double> scaled;
  const BlockSink rate_blocks = [&](std::span<const double> block) {
    if (!scale_to_si) scale_to_si.emplace(plan.input, report->record.units);
    if (scale_to_si->identity()) {
      stream.Add(block);
      return;
    }
    scaled.resize(block.size());
    for (std::size_t k = 0; k < block.size(); ++k) scaled[k] = (*scale_to_si)(block[k]);
    stream.Add(scaled);
  };
  const bool ok = ReadRecord(
      plan.read,
      [&](double v) {
        if (!scale_to_si) scale_to_si.emplace(plan.input, report->record.units);
        if (!angle) {
          stream.Add((*scale_to_si)(v));
          return;
        }
        const double a = (*scale_to_si)(v);
        if (have_previous) stream.Add(a - previous);
        previous = a;
        have_previous = true;
      },
      &report->record, &error, angle ? nullptr : &rate_blocks);
  if (!ok) return Failure{error.exit_code, error.message};
  report->input_units = report->record.units;
  return StreamedCurve(plan, stream, angle, exact_max_m, report);
}

// One column of a several-column read, streamed: its samples to SI (ColumnToSi's arithmetic,
// one value at a time) and, for a gyro's angle, differenced into the estimator.
class StreamedColumn {
 public:
  StreamedColumn(const Plan& plan, const ColumnInfo& c, std::int64_t exact_max_m)
      : stream_(estimators::StreamingAvarOptions{exact_max_m}),
        gyro_(c.sensor == ImuSensor::kGyro),
        angle_(gyro_ && plan.input == InputKind::kAngle),
        gyro_scale_(plan.input, gyro_ ? c.units : std::string("rad/s")) {
    if (!gyro_) ParseAccelUnit(c.units, &accel_, nullptr);  // canonical: always parses
  }
  void Add(double v) {
    const double si = gyro_ ? gyro_scale_(v) : AccelToSi(accel_, v);
    if (!angle_) {
      stream_.Add(si);
      return;
    }
    if (have_previous_) stream_.Add(si - previous_);
    previous_ = si;
    have_previous_ = true;
  }
  const estimators::StreamingAvar& stream() const { return stream_; }
  bool angle() const { return angle_; }

 private:
  estimators::StreamingAvar stream_;
  bool gyro_;
  bool angle_;
  InputScale gyro_scale_;
  AccelUnit accel_ = AccelUnit::kMeterPerSecond2;
  bool have_previous_ = false;
  double previous_ = 0.0;
};

// Every asked column streamed in one pass (bounded memory), one report each.
std::optional<Failure> ComputeColumnsStreamed(const Plan& plan, const std::string& taus_text,
                                              std::int64_t exact_max_m, std::vector<AvarReport>* reports) {
  RecordInfo info;
  RecordError error;
  // The columns and their units are known before the first row (record_reader.h).
  std::vector<StreamedColumn> columns;
  const bool ok = ReadRecordRows(
      plan.read,
      [&](std::span<const double> row) {
        if (columns.empty()) {
          for (const ColumnInfo& c : info.columns) columns.emplace_back(plan, c, exact_max_m);
        }
        for (std::size_t k = 0; k < row.size(); ++k) columns[k].Add(row[k]);
      },
      &info, &error);
  if (!ok) return Failure{error.exit_code, error.message};
  if (columns.empty()) {
    for (const ColumnInfo& c : info.columns) columns.emplace_back(plan, c, exact_max_m);
  }
  reports->assign(info.columns.size(), AvarReport());
  for (std::size_t k = 0; k < info.columns.size(); ++k) {
    AvarReport& r = (*reports)[k];
    DescribeColumn(plan, info, k, taus_text, &r);
    if (auto failure = StreamedCurve(plan, columns[k].stream(), columns[k].angle(), exact_max_m, &r)) return failure;
  }
  return std::nullopt;
}

void WarnAboutRecord(const RecordInfo& info, const std::string& command) {
  if (info.dropped_nonfinite > 0) {
    PrintWarning(info.path + ": dropped " + std::to_string(info.dropped_nonfinite) +
                     " non-finite value(s) (--drop-nonfinite); the record is shorter by as many "
                     "samples and the curve treats it as contiguous",
                 command);
  }
  if (info.time.irregular_steps > 0) {
    PrintWarning(info.path + ": " + TimeSteps::Describe(info.time, info.time_column) +
                     "; the estimator assumes uniform sampling",
                 command);
  }
  if (info.columns.size() > 1) {
    for (const ColumnInfo& c : info.columns) {
      if (const auto stuck = DescribeConstantStretch(c.longest_constant_stretch, info.samples, info.sample_clock.rate_hz())) {
        PrintWarning(info.path + ": column " + c.name + ": " + *stuck, command);
      }
    }
  } else if (const auto stuck = DescribeConstantStretch(info.longest_constant_stretch, info.samples, info.sample_clock.rate_hz())) {
    PrintWarning(info.path + ": " + *stuck, command);
  }
}

}  // namespace

void AddRecordCurveOptions(CLI::App* cmd, RecordCurveOptions* options) {
  cmd->add_option("FILE", options->path,
                  "the record ('-' for standard input): CSV/TSV/whitespace text with '#' comments "
                  "and an optional header, or raw little-endian float32/float64 (--format); "
                  "plain, .gz or .xz (detected from the content)")
      ->required()
      ->type_name("");
  cmd->add_option("--column", options->column,
                  "text column by header name or 0-based index (default: the first column that "
                  "is not the time column t, t_s, time, time_s, timestamp, t_ms, time_ns, %time "
                  "...; without a header, a first column that increases is the time in seconds); "
                  "an accelerometer axis (Accel_X) is read in its own units, as with --columns")
      ->type_name("NAME|INDEX");
  cmd->add_option("--columns", options->columns,
                  "several columns, read in one pass, each with its own curve: a comma list of "
                  "names or 0-based indices (Gyro_X,Gyro_Y,Gyro_Z); a column whose name starts "
                  "acc (Accel_X) or is a ROS linear_acceleration is an accelerometer axis, any "
                  "other a gyro axis")
      ->type_name("LIST");
  cmd->add_flag("--imu", options->imu,
                "every gyro and accelerometer column, recognised by name (a word starting gyr or "
                "acc, ROS angular_velocity and linear_acceleration)");
  cmd->add_option("--units", options->units,
                  "input units: deg/s, deg/h or rad/s for rate; deg, rad or arcsec for angle. "
                  "Needed unless the file states them (a unit in the column name such as "
                  "Gyro_X_dps or rate_rad_per_s, a '# units: rad/s' line, or the .json sidecar of "
                  "a raw record); when both do, they must agree")
      ->type_name("UNIT");
  cmd->add_option("--out-units", options->out_units,
                  "units of the printed deviation: deg/h (default), deg/s or rad/s")
      ->type_name("deg/h|deg/s|rad/s");
  cmd->add_option("--accel-units", options->accel_units,
                  "input units of accelerometer columns: m/s^2, g or mg. Needed unless the file "
                  "states them (Accel_X_g, acc_x_mps2, a ROS linear_acceleration, a '# units: g' "
                  "line); when both do, they must agree")
      ->type_name("UNIT");
  cmd->add_option("--accel-out-units", options->accel_out_units,
                  "units of an accelerometer's printed deviation: mg (default), g or m/s^2")
      ->type_name("mg|g|m/s^2");
  cmd->add_option("--topic", options->topic,
                  "the sensor_msgs/Imu topic of a ROS bag (MCAP, ROS 2 .db3 or ROS 1 .bag; default: "
                  "the bag's only Imu topic). Its columns: angular_velocity.x/y/z (rad/s), "
                  "linear_acceleration.x/y/z (m/s^2), timed by the message header stamps")
      ->type_name("TOPIC");
  cmd->add_option("--rate", options->rate_hz,
                  "sample rate in Hz; needed without a time column or a raw record's sidecar; "
                  "with one it must agree to 1e-3 relative")
      ->type_name("HZ");
  cmd->add_option("--time-units", options->time_units,
                  "unit of the time column (default: from its name: t_ms, time_us, time_ns, "
                  "%time (ROS, ns) ...; bare t, time, timestamp are seconds)")
      ->type_name("s|ms|us|ns");
  cmd->add_option("--type", options->type, "the column holds rate (default) or angle samples")
      ->type_name("rate|angle");
  cmd->add_option("--taus", options->taus,
                  "octave (default), decade (1-2-5), dense:K (K per decade), all (slow: O(N^2)), "
                  "or a comma list of taus in seconds")
      ->type_name("GRID");
  cmd->add_option("--confidence", options->confidence,
                  "two-sided level of the intervals (default 0.683)")
      ->type_name("P");
  cmd->add_option_function<std::string>(
         "--ci", [options](const std::string& v) { options->ci = v; },
         "interval method: auto (default: the EDF measured on the record's own differences "
         "where they are numerous, else Greenhall-Riley at the identified noise type, held "
         "from the shorter tau where few averages cannot tell), gr (Greenhall-Riley EDF at the "
         "noise type identified at each tau alone, as Stable32), simple (EDF = clusters - 1, "
         "IEEE 952; the default with --stream) or none")
      ->type_name("auto|gr|simple|none");
  cmd->add_option("--format", options->format,
                  "input record format: text, f32 or f64 (raw little-endian); default: text, or "
                  "what the raw record's .json sidecar says")
      ->type_name("text|f32|f64");
  cmd->add_flag("--drop-nonfinite", options->drop_nonfinite,
                "skip rows whose value is NaN, inf or missing (counted and reported) instead of "
                "failing");
}

int CheckRecordCurveOptions(const RecordCurveOptions& options, std::string* error) {
  Plan plan;
  if (std::optional<Failure> failure = MakePlan(options, &plan)) {
    *error = failure->message;
    return failure->code;
  }
  return kExitOk;
}

int ComputeCurveFromFile(const RecordCurveOptions& options, const std::string& command,
                         AvarReport* report, std::string* error) {
  if (SeveralColumns(options)) {
    *error = "`" + command + "` reads one column here: give --column NAME";
    return kExitUsageError;
  }
  Plan plan;
  std::optional<Failure> failure = MakePlan(options, &plan);
  if (!failure) {
    report->output_unit = plan.output_unit;
    report->taus_text = options.taus;
    failure = options.stream ? ComputeStreamed(plan, options.stream_exact_max_m, report)
                             : ComputeInMemory(plan, report);
  }
  if (failure) {
    *error = failure->message;
    return failure->code;
  }
  WarnAboutRecord(report->record, command);
  return kExitOk;
}

int ComputeCurveFromSamples(const RecordCurveOptions& options, std::vector<double> values,
                            AvarReport* report, std::string* error) {
  Plan plan;
  std::optional<Failure> failure;
  if (SeveralColumns(options) || options.stream) failure = Usage("one column in memory: no columns, imu or stream");
  if (!failure) failure = MakePlan(options, &plan);
  if (!failure) failure = DescribeSamples(options, plan, values, &report->record);
  if (!failure) {
    report->output_unit = plan.output_unit;
    report->taus_text = options.taus;
    values.insert(values.begin(), 0.0);  // the spare slot
    failure = CurveOfValues(plan, values, report);
  }
  if (failure) {
    *error = failure->message;
    return failure->code;
  }
  report->input_units = report->record.units;
  return kExitOk;
}

int RateFromSamples(const RecordCurveOptions& options, std::vector<double>* values, RecordInfo* info,
                    std::string* error) {
  Plan plan;
  std::optional<Failure> failure;
  if (SeveralColumns(options) || options.stream) failure = Usage("one column in memory: no columns, imu or stream");
  if (!failure) failure = MakePlan(options, &plan);
  if (!failure) failure = DescribeSamples(options, plan, *values, info);
  if (failure) {
    *error = failure->message;
    return failure->code;
  }
  RateToSi(plan, *info, values);
  return kExitOk;
}

bool SeveralColumns(const RecordCurveOptions& options) {
  return options.imu || !options.columns.empty() || options.column.find(',') != std::string::npos ||
         ImuSensorOfColumn(options.column) == ImuSensor::kAccelerometer;
}

int ComputeCurvesFromFile(const RecordCurveOptions& options, const std::string& command,
                          std::vector<AvarReport>* reports, std::string* error) {
  Plan plan;
  std::optional<Failure> failure = MakePlan(options, &plan);
  if (!failure) {
    failure = options.stream ? ComputeColumnsStreamed(plan, options.taus, options.stream_exact_max_m, reports)
                             : ComputeColumnsInMemory(plan, options.taus, reports);
  }
  if (failure) {
    *error = failure->message;
    return failure->code;
  }
  WarnAboutRecord(reports->front().record, command);
  return kExitOk;
}

int ReadRateFromFile(const RecordCurveOptions& options, const std::string& command,
                     std::vector<double>* rate, RecordInfo* info, std::string* error) {
  if (SeveralColumns(options)) {
    *error = "`" + command + "` reads one column here: give --column NAME";
    return kExitUsageError;
  }
  Plan plan;
  if (std::optional<Failure> failure = MakePlan(options, &plan)) {
    *error = failure->message;
    return failure->code;
  }
  RecordError read_error;
  if (!ReadRecordValues(plan.read, rate, info, &read_error)) {
    *error = read_error.message;
    return read_error.exit_code;
  }
  RateToSi(plan, *info, rate);
  WarnAboutRecord(*info, command);
  return kExitOk;
}

int ReadRatesFromFile(const RecordCurveOptions& options, const std::string& command,
                      std::vector<std::vector<double>>* rates, RecordInfo* info, std::string* error) {
  Plan plan;
  if (std::optional<Failure> failure = MakePlan(options, &plan)) {
    *error = failure->message;
    return failure->code;
  }
  RecordError read_error;
  if (!ReadRecordColumns(plan.read, rates, info, &read_error)) {
    *error = read_error.message;
    return read_error.exit_code;
  }
  for (std::size_t k = 0; k < rates->size(); ++k) {
    ColumnToSi(plan, info->columns[k], &(*rates)[k]);
    if (info->columns[k].sensor == ImuSensor::kGyro && plan.input == InputKind::kAngle) {
      (*rates)[k] = estimators::AngleToRate((*rates)[k], info->sample_clock.period_s());
    }
  }
  WarnAboutRecord(*info, command);
  return kExitOk;
}

}  // namespace allanlab::app
