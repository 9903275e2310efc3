#include "app/reports/simulated_record.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <new>
#include <nlohmann/json.hpp>
#include <span>
#include <utility>
#include <vector>

#include "app/reports/allan_plot.h"
#include "common/atomic_file.h"
#include "app/reports/output_paths.h"
#include "app/reports/provenance.h"
#include "app/input/rate_units.h"
#include "common/number_text.h"
#include "estimators/allan_variance.h"
#include "sim/sensor_model.h"
#include "sim/sensor_spec.h"
#include "sim/units.h"

namespace allanlab::app {
namespace {

constexpr const char* kCommand = "simulate";  // the provenance names the command that wrote the record

enum class RecordFormat { kCsv, kFloat64 };

using Failure = CommandFailure;

Failure Usage(std::string message) { return UsageFailure(std::move(message)); }
Failure Runtime(std::string message) { return RuntimeFailure(std::move(message)); }

std::string Join(const std::vector<std::string>& items, const char* separator) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? separator : "") + items[i];
  return out;
}

}  // namespace

std::string PresetList() { return Join(sim::PresetNames(), ", "); }

namespace {

bool PositiveFinite(double value) { return std::isfinite(value) && value > 0.0; }

// Appends the shortest round-trip text of `value`: every double reads back bit-exactly.
void AppendNumber(std::string* out, double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out->append(buffer, result.ptr);
}

// Writes in blocks so that a long record never needs its whole text in memory.
class BlockWriter {
 public:
  explicit BlockWriter(std::ostream& os) : os_(os) { buffer_.reserve(kBlock + 256); }
  ~BlockWriter() { Flush(); }
  std::string* buffer() { return &buffer_; }
  void MaybeFlush() {
    if (buffer_.size() >= kBlock) Flush();
  }
  void Flush() {
    os_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    buffer_.clear();
  }

 private:
  static constexpr std::size_t kBlock = 1 << 20;
  std::ostream& os_;
  std::string buffer_;
};

void WriteCsvRecord(std::ostream& os, const std::string& provenance_lines,
                    std::span<const double> rate_in_unit, double rate_hz, RateUnit unit) {
  BlockWriter writer(os);
  std::string* out = writer.buffer();
  *out += provenance_lines;
  *out += "time_s,rate_" + std::string(RateUnitIdentifier(unit)) + "\n";
  for (std::size_t k = 0; k < rate_in_unit.size(); ++k) {
    AppendNumber(out, static_cast<double>(k) / rate_hz);
    *out += ',';
    AppendNumber(out, rate_in_unit[k]);
    *out += '\n';
    writer.MaybeFlush();
  }
}

void WriteFloat64Record(std::ostream& os, std::span<const double> rate_in_unit) {
  BlockWriter writer(os);
  std::string* out = writer.buffer();
  for (double value : rate_in_unit) {
    std::uint64_t bits = std::bit_cast<std::uint64_t>(value);
    if constexpr (std::endian::native == std::endian::big) bits = __builtin_bswap64(bits);
    char bytes[sizeof bits];
    std::memcpy(bytes, &bits, sizeof bits);
    out->append(bytes, sizeof bytes);
    writer.MaybeFlush();
  }
}

// Octave Allan numbers of one record: what the plot draws and the table lists.
struct AllanNumbers {
  std::vector<std::int64_t> ms;
  std::vector<double> tau_s;
  std::vector<double> oavar_sim;    // (rad/s)^2
  std::vector<double> oavar_exact;  // (rad/s)^2, E[estimator] for this record length
  std::vector<double> oavar_ieee;   // (rad/s)^2, continuous asymptote
};

AllanNumbers ComputeAllanNumbers(const sim::SensorModel& model,
                                 std::span<const double> rate_rad_s) {
  AllanNumbers a;
  const auto n = static_cast<std::int64_t>(rate_rad_s.size());
  a.ms = estimators::OctaveAveragingFactors(n / 8);
  a.oavar_sim = estimators::AllanVariance(rate_rad_s, a.ms, sim::AvarEstimatorKind::kOverlapping);
  a.oavar_exact =
      model.ExpectedAvar(a.ms, sim::RecordShape{n, sim::AvarEstimatorKind::kOverlapping});
  for (std::int64_t m : a.ms) {
    const double tau = static_cast<double>(m) / model.sample_clock.rate_hz();
    a.tau_s.push_back(tau);
    a.oavar_ieee.push_back(model.AsymptoticAvar(tau));
  }
  return a;
}

double AdevDegPerHour(double avar_rad2_per_s2) {
  return units::ToDegPerHour(std::sqrt(std::max(avar_rad2_per_s2, 0.0)));
}

void WriteAvarTable(std::ostream& os, const std::string& provenance_lines, const AllanNumbers& a) {
  BlockWriter writer(os);
  std::string* out = writer.buffer();
  *out += provenance_lines;
  *out += "m,tau_s,oavar_sim,oavar_exact,oavar_ieee,adev_sim_deg_per_h,adev_exact_deg_per_h\n";
  for (std::size_t i = 0; i < a.ms.size(); ++i) {
    *out += std::to_string(a.ms[i]);
    for (double v : {a.tau_s[i], a.oavar_sim[i], a.oavar_exact[i], a.oavar_ieee[i],
                     AdevDegPerHour(a.oavar_sim[i]), AdevDegPerHour(a.oavar_exact[i])}) {
      *out += ',';
      AppendNumber(out, v);
    }
    *out += '\n';
  }
}

AllanPlot MakePlot(const AllanNumbers& a, const sim::SensorModel& model, const std::string& source,
                   std::uint64_t seed, std::uint64_t trial, std::int64_t n) {
  AllanPlot plot;
  plot.title = "allanlab simulate: " + source + ", seed " + std::to_string(seed) + ", trial " +
               std::to_string(trial) + " (" + std::to_string(n) + " samples at " +
               ShortestDecimal(model.sample_clock.rate_hz()) + " Hz)";
  PlotSeries sim{"simulated (overlapping ADEV)", PlotStyle::kPoints, a.tau_s, {}};
  PlotSeries exact{
      model.ExpectedAvarIsExact() ? "exact theory" : "theory (quantizers approximated)",
      PlotStyle::kLine,
      a.tau_s,
      {}};
  for (std::size_t i = 0; i < a.ms.size(); ++i) {
    sim.y.push_back(AdevDegPerHour(a.oavar_sim[i]));
    exact.y.push_back(AdevDegPerHour(a.oavar_exact[i]));
  }
  // The asymptote is a closed form, so it is drawn smoothly, 20 points per decade.
  PlotSeries ieee{"IEEE 952 asymptote", PlotStyle::kDashedLine, {}, {}};
  const double tau_lo = a.tau_s.front(), tau_hi = a.tau_s.back();
  const int steps = std::max(2, static_cast<int>(std::ceil(20 * std::log10(tau_hi / tau_lo))));
  for (int i = 0; i <= steps; ++i) {
    const double tau = tau_lo * std::pow(tau_hi / tau_lo, static_cast<double>(i) / steps);
    ieee.x.push_back(tau);
    ieee.y.push_back(AdevDegPerHour(model.AsymptoticAvar(tau)));
  }
  // Order: guides hug the exact curve (series 0); simulated points are drawn last, on top.
  plot.series = {std::move(exact), std::move(ieee), std::move(sim)};
  plot.guide_series = 0;
  return plot;
}

}  // namespace

// Usage errors are the user's (bad name, --rate), runtime errors the file's.
std::optional<CommandFailure> LoadSimulateModel(const SimulateOptions& o, sim::SensorModel* model) {
  std::string why;
  if (o.preset.empty() == o.sensor_path.empty()) {
    return Usage("give exactly one of --preset NAME or --sensor SPEC.yaml");
  }
  if (o.rate_hz && !PositiveFinite(*o.rate_hz)) {
    return Usage("--rate must be a finite number of Hz > 0, got " + ShortestDecimal(*o.rate_hz));
  }
  if (!o.preset.empty()) {
    const std::vector<std::string> names = sim::PresetNames();
    if (std::find(names.begin(), names.end(), o.preset) == names.end()) {
      return Usage("unknown preset '" + o.preset + "' (known: " + PresetList() + ")");
    }
    if (!sim::LoadPreset(o.preset, model, &why)) return Runtime("preset " + o.preset + ": " + why);
  } else if (!sim::LoadSensorModelFile(o.sensor_path, model, &why)) {
    return Runtime(why);
  }
  if (o.rate_hz) {
    model->sample_clock = SampleClock::FromRateHz(*o.rate_hz);
    if (!model->IsValid(&why)) {
      return Usage("--rate " + ShortestDecimal(*o.rate_hz) +
                   " Hz does not suit the sensor: " + why);
    }
  }
  return std::nullopt;
}

std::optional<CommandFailure> SimulateSampleCount(const SimulateOptions& o, double sample_rate_hz,
                                                  std::int64_t* n) {
  if (!PositiveFinite(o.duration_s)) {
    return Usage("--duration must be a finite number of seconds > 0, got " + ShortestDecimal(o.duration_s));
  }
  const double fs = sample_rate_hz;
  const double samples = std::round(o.duration_s * fs);
  // 2^53: beyond it sample times are no longer exact in a double, and no machine holds it anyway.
  if (!(samples <= 9007199254740992.0)) {
    return Usage("--duration " + ShortestDecimal(o.duration_s) + " s at " + ShortestDecimal(fs) +
                 " Hz is too many samples");
  }
  *n = static_cast<std::int64_t>(samples);
  if (*n < kMinSimulateSamples) {
    return Usage("--duration " + ShortestDecimal(o.duration_s) + " s at " + ShortestDecimal(fs) +
                 " Hz gives " + std::to_string(*n) + " samples; at least " +
                 std::to_string(kMinSimulateSamples) +
                 " are needed (duration >= " + ShortestDecimal(kMinSimulateSamples / fs) + " s)");
  }
  return std::nullopt;
}

std::optional<CommandFailure> WriteSimulatedRecord(const SimulateOptions& o, const std::string& command_line) {
  // 1. The command line on its own.
  const std::string extension = std::filesystem::path(o.output_path).extension().string();
  const std::string named = extension == ".f64" ? "f64" : extension == ".csv" ? "csv" : "";
  const std::string format_id = o.format.empty() ? (named.empty() ? "csv" : named) : o.format;
  if (format_id != "csv" && format_id != "f64") {
    return Usage("unknown --format '" + o.format + "' (expected csv or f64)");
  }
  if (!named.empty() && named != format_id) {
    return Usage("--format " + format_id + " contradicts the output name " + o.output_path +
                 " (a " + extension + " file); drop --format or rename the output");
  }
  const RecordFormat format = format_id == "csv" ? RecordFormat::kCsv : RecordFormat::kFloat64;
  RateUnit unit;
  std::string why;
  if (!ParseRateUnit(o.units, &unit, &why)) return Usage("--units: " + why);
  if (o.output_path.empty()) return Usage("-o OUT is required");

  // 2. The sensor and the record length.
  sim::SensorModel model;
  if (auto failure = LoadSimulateModel(o, &model)) return failure;
  const double fs = model.sample_clock.rate_hz();
  std::int64_t n = 0;
  if (auto failure = SimulateSampleCount(o, fs, &n)) return failure;

  // 3. Every output opened before the work, so that a bad path or a missing gnuplot costs nothing.
  const std::string sidecar_path = o.output_path + ".json";
  std::vector<std::pair<std::string, std::string>> outputs = {{"-o", o.output_path}};
  if (format == RecordFormat::kFloat64) outputs.emplace_back("-o (sidecar)", sidecar_path);
  if (!o.plot_path.empty()) outputs.emplace_back("--plot", o.plot_path);
  if (!o.avar_table_path.empty()) outputs.emplace_back("--avar-table", o.avar_table_path);
  if (!CheckDistinctOutputs(outputs, &why)) return Usage(why);
  if (!o.plot_path.empty() && !FindGnuplot(&why)) return Runtime(why);
  AtomicFile record, sidecar, plot_png, table;
  if (!record.Open(o.output_path, &why)) return Runtime(why);
  if (format == RecordFormat::kFloat64 && !sidecar.Open(sidecar_path, &why)) return Runtime(why);
  if (!o.plot_path.empty() && !plot_png.Open(o.plot_path, &why)) return Runtime(why);
  if (!o.avar_table_path.empty() && !table.Open(o.avar_table_path, &why)) return Runtime(why);

  // 4. The record.
  std::vector<double> rate;
  try {
    rate = model.Generate(o.seed, o.trial, n);
  } catch (const std::bad_alloc&) {
    return Runtime("not enough memory for " + std::to_string(n) + " samples");
  }
  Provenance provenance = MakeProvenance(kCommand, command_line);
  const std::string source = o.preset.empty() ? "spec " + o.sensor_path : "preset " + o.preset;
  if (o.preset.empty()) {
    provenance.Add("sensor_spec", o.sensor_path);
  } else {
    provenance.Add("preset", o.preset);
  }
  provenance.Add("sensor_name", model.name);
  provenance.Add("seed", std::to_string(o.seed));
  provenance.Add("trial", std::to_string(o.trial));
  provenance.Add("sample_rate",
                 ShortestDecimal(fs) + " Hz" + (o.rate_hz ? " (--rate)" : " (spec)"));
  provenance.Add("duration", ShortestDecimal(o.duration_s) + " s");
  provenance.Add("samples", std::to_string(n));
  provenance.Add("units", std::string(RateUnitName(unit)));

  // 5. The Allan numbers come from the record in rad/s, before any unit conversion.
  std::optional<AllanNumbers> allan;
  if (plot_png.is_open() || table.is_open()) allan = ComputeAllanNumbers(model, rate);

  for (double& value : rate) value = FromRadPerSecond(unit, value);
  if (format == RecordFormat::kCsv) {
    WriteCsvRecord(record.stream(), ProvenanceCommentLines(provenance), rate, fs, unit);
  } else {
    WriteFloat64Record(record.stream(), rate);
    nlohmann::ordered_json j;
    j["provenance"] = ProvenanceJson(provenance);
    j["data"] = {
        {"file", std::filesystem::path(o.output_path).filename().string()},
        {"layout", "raw float64, little-endian, one rate sample per value, no header"},
        {"dtype", "<f8"},
        {"num_samples", n},
        {"sample_rate_hz", fs},
        {"sample_time_s", "k / sample_rate_hz, k = 0 .. num_samples-1"},
        {"quantity", "angular rate"},
        {"units", RateUnitName(unit)},
    };
    sidecar.stream() << j.dump(2) << "\n";
  }

  if (table.is_open()) {
    Provenance table_provenance = provenance;
    table_provenance.Add("estimator", "overlapping Allan variance at octave m <= N/8");
    table_provenance.Add(
        "columns",
        std::string("tau_s = m / sample_rate [s]; oavar_* in (rad/s)^2; adev_* in deg/h; ") +
            (model.ExpectedAvarIsExact()
                 ? "oavar_exact = exact E[estimator] for this N"
                 : "oavar_exact approximates the output quantizers' share") +
            "; oavar_ieee = IEEE 952 asymptote");
    WriteAvarTable(table.stream(), ProvenanceCommentLines(table_provenance), *allan);
  }
  if (plot_png.is_open() &&
      !RenderAllanPlot(MakePlot(*allan, model, source, o.seed, o.trial, n), &plot_png, &why)) {
    return Runtime(why);
  }

  // 6. Commit. Data first and the record last, so that the record's presence means the run
  // finished.
  for (AtomicFile* file : {&table, &plot_png, &sidecar, &record}) {
    if (file->is_open() && !file->Commit(&why)) return Runtime(why);
  }
  return std::nullopt;
}

}  // namespace allanlab::app
