#include "app/commands/diagnosis_benchmark_command.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/reports/allan_plot.h"
#include "common/atomic_file.h"
#include "app/reports/provenance.h"
#include "app/input/record_reader.h"
#include "app/reports/simulated_record.h"
#include "experiments/diagnosis/benchmark_case.h"
#include "experiments/diagnosis/benchmark_report.h"
#include "experiments/diagnosis/benchmark_score.h"
#include "experiments/diagnosis/independent_case.h"
#include "independent/generate.h"
#include "sim/embedded_presets.h"
#include "sim/sensor_spec.h"
#include "common/number_text.h"

namespace allanlab::app {
namespace {

constexpr const char* kCommand = "diagnosis-benchmark";
namespace fs = std::filesystem;
using namespace allanlab::experiments;

// The case's model as a sensor spec `simulate --sensor` reads: the preset's text without its
// band-limit and output quantizers, plus the effect (SI units throughout).
bool SpecYaml(const BenchmarkCase& c, std::string* yaml, std::string* why) {
  std::string_view preset;
  for (const auto& p : sim::EmbeddedPresets()) {
    if (p.name == c.preset) preset = p.yaml;
  }
  if (preset.empty()) {
    *why = "no embedded preset " + c.preset;
    return false;
  }
  std::vector<std::string> lines;
  std::istringstream in{std::string(preset)};
  std::size_t last_term = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("band_limit:", 0) == 0 || line.rfind("output:", 0) == 0) continue;
    lines.push_back(line);
    if (line.rfind("  - {type:", 0) == 0) last_term = lines.size();
  }
  std::ostringstream extra, term;
  if (c.effect) {
    const auto& p = c.effect->params;
    switch (c.effect->effect) {
      case Effect::kBandwidth:
        extra << "band_limit: {type: " << sim::LowPassKindName(c.model.band_limit.kind)
              << ", cutoff: " << SignificantDigits(p.at("cutoff_hz"), 17) << " Hz, oversampling: " << c.model.band_limit.oversampling
              << ", sampling: " << (c.model.band_limit.sampling == sim::OutputSampling::kAverage ? "average" : "point")
              << "}\n";
        break;
      case Effect::kAngleQuantization:
        extra << "output: {angle_lsb: " << SignificantDigits(p.at("lsb_rad"), 17) << " rad}\n";
        break;
      case Effect::kRateQuantization:
        extra << "output: {rate_lsb: " << SignificantDigits(p.at("lsb_rad_per_s"), 17) << " rad/s}\n";
        break;
      case Effect::kGaussMarkov:
        term << "  - {type: gauss_markov, sigma: " << SignificantDigits(p.at("sigma_rad_per_s"), 17) << " rad/s, correlation_time: "
             << SignificantDigits(p.at("correlation_time_s"), 17) << " s}";
        break;
      case Effect::kRandomTelegraph:
        term << "  - {type: random_telegraph, amplitude: " << SignificantDigits(p.at("amplitude_rad_per_s"), 17)
             << " rad/s, mean_dwell: " << SignificantDigits(p.at("mean_dwell_s"), 17) << " s}";
        break;
      case Effect::kResonance:
        term << "  - {type: resonance, sigma: " << SignificantDigits(p.at("sigma_rad_per_s"), 17) << " rad/s, frequency: "
             << SignificantDigits(p.at("frequency_hz"), 17) << " Hz, damping: " << SignificantDigits(p.at("damping"), 17) << "}";
        break;
      case Effect::kHarmonic:
        term << "  - {type: harmonic, amplitude: " << SignificantDigits(p.at("amplitude_rad_per_s"), 17) << " rad/s, frequency: "
             << SignificantDigits(p.at("frequency_hz"), 17) << " Hz}";
        break;
      case Effect::kExponentialDrift:
        term << "  - {type: exponential_drift, amplitude: " << SignificantDigits(p.at("amplitude_rad_per_s"), 17)
             << " rad/s, time_constant: " << SignificantDigits(p.at("time_constant_s"), 17) << " s}";
        break;
      case Effect::kBiasStep:
        term << "  - {type: bias_step, size: " << SignificantDigits(p.at("size_rad_per_s"), 17) << " rad/s, time: "
             << SignificantDigits(p.at("time_s"), 17) << " s}";
        break;
      case Effect::kOutliers:
        term << "  - {type: outliers, rate: " << SignificantDigits(p.at("rate_hz"), 17) << " Hz, size: "
             << SignificantDigits(p.at("size_rad_per_s"), 17) << " rad/s}";
        break;
    }
  }
  if (!term.str().empty()) lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(last_term), term.str());
  std::ostringstream out;
  out << "# allanlab diagnosis-benchmark recording " << c.index << ": preset " << c.preset
      << " (IEEE 952 terms) + " << (c.effect ? EffectId(c.effect->effect) : "no effect") << "\n";
  for (const auto& line : lines) out << line << "\n";
  out << extra.str();
  *yaml = out.str();
  // The spec must be the model whose strength was measured.
  sim::SensorModel loaded;
  if (!sim::LoadSensorModelYaml(*yaml, "benchmark spec", &loaded, why)) return false;
  loaded.sample_clock = c.sample_clock;
  const sim::RecordShape shape{c.num_samples, sim::AvarEstimatorKind::kOverlapping};
  for (std::int64_t m : {1, 10, 100, 1000}) {
    const double a = loaded.ExpectedAvar(m, shape), b = c.model.ExpectedAvar(m, shape);
    if (!(std::abs(a - b) <= 1e-9 * std::abs(b))) {
      std::ostringstream os;
      os << "recording " << c.index << ": the written spec differs from the drawn model at m = " << m << " (" << a
         << " vs " << b << ")";
      *why = os.str();
      return false;
    }
  }
  return true;
}

// What the diagnosis said, from its JSON.
BenchmarkOutcome ReadOutcome(const std::string& path) {
  BenchmarkOutcome o;
  std::ifstream in(path);
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const std::exception& e) {
    o.failure = "unreadable diagnosis JSON: " + std::string(e.what());
    return o;
  }
  o.ok = true;
  o.significant = j["gap"]["significant"].get<bool>();
  o.threshold_z = j["gap"]["threshold_z"].get<double>();
  for (const auto& r : j["gap"]["regions"]) {
    o.regions.push_back({r["view"].get<std::string>(), r["tau_min_s"].get<double>(), r["tau_max_s"].get<double>()});
  }
  o.verdict = j["verdict"]["effect"].get<std::string>();
  for (const auto& a : j["verdict"]["also_consistent"]) o.also_consistent.push_back(a.get<std::string>());
  for (const auto& c : j["candidates"]) {
    if (c["effect"].get<std::string>() != o.verdict) continue;
    if (c["heldout_gap_before"].is_object() && c["heldout_gap_after"].is_object()) {
      o.has_heldout = true;
      o.heldout_before_chi2 = c["heldout_gap_before"]["chi2"].get<double>();
      o.heldout_after_chi2 = c["heldout_gap_after"]["chi2"].get<double>();
      o.heldout_points = c["heldout_gap_after"]["points"].get<int>();
    }
    break;
  }
  return o;
}

// Detection and right-effect rates per strength bin, with their intervals: strength on a log
// axis, rates on a linear one (a rate's whole range, 0 to 1, reads at a glance there).
AllanPlot RatePlot(const BenchmarkSummary& s, std::uint64_t seed, int recordings) {
  AllanPlot plot;
  std::ostringstream title;
  title << "allanlab diagnosis-benchmark: " << recordings << " recordings, seed " << seed
        << " (strength bins with recordings)";
  plot.title = title.str();
  plot.x_label = "strength: expected peak gap z";
  plot.y_label = "rate (95 % Wilson interval)";
  plot.log_y = false;
  plot.key = "bottom right opaque";
  plot.y_lines = {0.0, 1.0};
  plot.slope_guides = {};
  plot.guide_series = -1;
  PlotSeries det{"detected", PlotStyle::kPoints, {}, {}}, right{"right effect", PlotStyle::kPoints, {}, {}};
  for (const StrengthBin& b : s.bins) {
    if (b.detected.trials == 0) continue;
    const double x = b.lo <= 0.0 ? 0.5 : (b.hi > 1e100 ? 2.0 * b.lo : std::sqrt(b.lo * b.hi));
    det.x.push_back(x);
    det.y.push_back(b.detected.rate());
    det.y_low.push_back(b.detected.low);
    det.y_high.push_back(b.detected.high);
    right.x.push_back(x * 1.05);
    right.y.push_back(b.right.rate());
    right.y_low.push_back(b.right.low);
    right.y_high.push_back(b.right.high);
  }
  plot.series = {det, right};
  return plot;
}

// One recording ready to diagnose: its descriptor, its record on disk and where the diagnosis goes.
struct Prepared {
  BenchmarkCase c;
  fs::path record, json, log;
  std::vector<std::string> diagnose_args;  // after FILE: format, rate, units, the user's model
  bool reusable = false;                   // an earlier run's diagnosis of this very record is used
  BenchmarkOutcome reused;
};

// Writes recording i's record (and anything else it needs) into the work directory and fills
// *p; nullopt on success.
using PrepareRecording = std::function<std::optional<CommandFailure>(int i, Prepared* p)>;

struct RunResult {
  std::vector<BenchmarkRow> rows;
  std::vector<std::string> timing_lines;
  int reused = 0;
  double cpu_s = 0.0;  // diagnose CPU (user + sys) over the recordings diagnosed in this run
};

// Diagnoses run as child processes of this very binary (`allanlab diagnose FILE ...`, the CLI
// itself), up to --jobs at a time, while the next recordings are prepared.
std::optional<CommandFailure> RunRecordings(const DiagnosisBenchmarkOptions& o, int count, const std::string& label,
                                            const PrepareRecording& prepare, RunResult* result) {
  std::error_code ec;
  const std::string self = fs::read_symlink("/proc/self/exe", ec).string();
  if (ec) return RuntimeFailure("cannot find the allanlab binary (/proc/self/exe): " + ec.message());
  struct Running {
    Prepared p;
    std::chrono::steady_clock::time_point start;
  };
  std::map<pid_t, Running> running;
  result->rows.assign(static_cast<std::size_t>(count), BenchmarkRow{});
  result->timing_lines.assign(static_cast<std::size_t>(count), "");
  int done = 0;
  auto reap = [&]() -> std::optional<CommandFailure> {
    int status = 0;
    rusage usage{};
    const pid_t pid = wait4(-1, &status, 0, &usage);
    if (pid < 0) return RuntimeFailure(std::string("wait4: ") + std::strerror(errno));
    auto it = running.find(pid);
    if (it == running.end()) return std::nullopt;
    Running& r = it->second;
    const double cpu = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                       1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - r.start).count();
    result->cpu_s += cpu;
    BenchmarkOutcome outcome;
    if (WIFEXITED(status) && WEXITSTATUS(status) == kExitOk) {
      outcome = ReadOutcome(r.p.json.string());
    } else {
      std::ifstream log(r.p.log);
      std::string last, line;
      while (std::getline(log, line)) last = line;
      outcome.failure = "diagnose failed: " + last;
    }
    const auto i = static_cast<std::size_t>(r.p.c.index);
    result->rows[i] = ScoreBenchmarkCase(r.p.c, outcome);
    const BenchmarkRow& row = result->rows[i];
    ++done;
    std::fprintf(stderr, "allanlab %s: %s %d/%d done: #%zu %s %s N=%lld strength %.3g (%s) -> %s%s (%.1f s CPU, %.1f s wall)\n",
                 kCommand, label.c_str(), done, count, i, r.p.c.preset.c_str(), row.truth.c_str(),
                 static_cast<long long>(r.p.c.num_samples), r.p.c.strength_z, r.p.c.strength_class.c_str(),
                 outcome.ok ? outcome.verdict.c_str() : outcome.failure.c_str(), row.right ? " [right]" : "", cpu, wall);
    std::ostringstream t;
    t << label << ',' << i << ',' << row.truth << ',' << r.p.c.num_samples << ',' << cpu << ',' << wall << '\n';
    result->timing_lines[i] = t.str();
    if (!o.keep_work) {
      fs::remove(r.p.record, ec);
      fs::remove(r.p.record.string() + ".json", ec);
    }
    running.erase(it);
    return std::nullopt;
  };
  for (int i = 0; i < count; ++i) {
    Prepared p;
    if (auto f = prepare(i, &p)) return f;
    if (p.reusable) {
      result->rows[static_cast<std::size_t>(i)] = ScoreBenchmarkCase(p.c, p.reused);
      ++result->reused;
      ++done;
      std::fprintf(stderr, "allanlab %s: %s %d/%d reused: #%d %s -> %s\n", kCommand, label.c_str(), done, count, i,
                   result->rows[static_cast<std::size_t>(i)].truth.c_str(), p.reused.verdict.c_str());
      continue;
    }
    while (static_cast<int>(running.size()) >= o.jobs) {
      if (auto f = reap()) return f;
    }
    std::vector<std::string> args = {self, "diagnose", p.record.string()};
    args.insert(args.end(), p.diagnose_args.begin(), p.diagnose_args.end());
    args.insert(args.end(), {"--json", p.json.string()});
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, p.log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    pid_t pid = 0;
    Running r{std::move(p), std::chrono::steady_clock::now()};
    const int err = posix_spawn(&pid, self.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (err != 0) return RuntimeFailure("cannot start diagnose: " + std::string(std::strerror(err)));
    running.emplace(pid, std::move(r));
  }
  while (!running.empty()) {
    if (auto f = reap()) return f;
  }
  return std::nullopt;
}

// An earlier run's diagnosis of the same record (same draw: same seed and options; checked by
// the record path and sample count its JSON names), when --reuse asks for it.
void MaybeReuse(const DiagnosisBenchmarkOptions& o, Prepared* p) {
  if (!o.reuse || !fs::exists(p->json)) return;
  BenchmarkOutcome outcome = ReadOutcome(p->json.string());
  std::ifstream in(p->json);
  nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  const bool same = !j.is_discarded() && j.contains("provenance") &&
                    j["provenance"].value("input", "") == p->record.string() &&
                    j["provenance"].value("samples", "") == std::to_string(p->c.num_samples);
  if (outcome.ok && same) {
    p->reusable = true;
    p->reused = outcome;
  }
}

void SetPaths(const fs::path& work, const std::string& stem, Prepared* p) {
  p->record = work / (stem + ".f64");
  p->json = work / (stem + ".diagnosis.json");
  p->log = work / (stem + ".diagnose.log");
}

// Raw little-endian float64, written whole to a temporary and renamed.
std::optional<CommandFailure> WriteF64(const fs::path& path, const std::vector<double>& y) {
  AtomicFile f;
  std::string why;
  if (!f.Open(path.string(), &why)) return RuntimeFailure(why);
  f.stream().write(reinterpret_cast<const char*>(y.data()), static_cast<std::streamsize>(y.size() * sizeof(double)));
  if (!f.Commit(&why)) return RuntimeFailure(why);
  return std::nullopt;
}

PrepareRecording SimPreparer(const DiagnosisBenchmarkOptions& o, const BenchmarkDrawOptions& draw, const fs::path& work) {
  return [&o, draw, work](int i, Prepared* p) -> std::optional<CommandFailure> {
    std::string why;
    if (!DrawBenchmarkCase(draw, o.seed, i, &p->c, &why)) return RuntimeFailure("recording " + std::to_string(i) + ": " + why);
    const std::string stem = "rec" + std::to_string(i);
    SetPaths(work, stem, p);
    // A free IEEE baseline: the sim generator's effects (a band-limit among them) are gaps from it.
    p->diagnose_args = {"--format", "f64", "--rate", SignificantDigits(p->c.sample_clock.rate_hz(), 17), "--units", "rad/s", "--model", "Q,N,B,K,R"};
    std::string yaml;
    if (!SpecYaml(p->c, &yaml, &why)) return RuntimeFailure(why);
    MaybeReuse(o, p);
    if (p->reusable) return std::nullopt;
    const fs::path spec = work / (stem + ".yaml");
    {
      std::ofstream out(spec);
      out << yaml;
      if (!out) return RuntimeFailure(spec.string() + ": cannot write");
    }
    SimulateOptions so;
    so.sensor_path = spec.string();
    so.rate_hz = p->c.sample_clock.rate_hz();
    so.duration_s = p->c.duration_s();
    so.seed = o.seed;
    so.trial = static_cast<std::uint64_t>(i);
    so.output_path = p->record.string();
    so.format = "f64";
    so.units = "rad/s";
    std::ostringstream sim_line;
    sim_line << "allanlab simulate --sensor " << spec.string() << " --rate " << SignificantDigits(p->c.sample_clock.rate_hz(), 17) << " --duration "
             << SignificantDigits(so.duration_s, 17) << " --seed " << o.seed << " --trial " << i << " --format f64 --units rad/s -o "
             << p->record.string();
    if (auto failure = WriteSimulatedRecord(so, sim_line.str())) {
      return CommandFailure{failure->code, "recording " + std::to_string(i) + ": " + failure->message};
    }
    return std::nullopt;
  };
}

// The user's model handed to diagnose with the independent recordings: the IEEE terms the
// generator used (N, B, K), free.
const std::vector<std::string> kIndependentModel = {"--model", "N,B,K"};

PrepareRecording IndependentPreparer(const DiagnosisBenchmarkOptions& o, const IndependentDrawOptions& draw,
                                     const fs::path& work) {
  return [&o, draw, work](int i, Prepared* p) -> std::optional<CommandFailure> {
    std::string why;
    IndependentCase c;
    if (!DrawIndependentCase(draw, o.seed, i, &c, &why)) return RuntimeFailure("independent recording " + std::to_string(i) + ": " + why);
    p->c = c.descriptor;
    SetPaths(work, "indep" + std::to_string(i), p);
    p->diagnose_args = {"--format", "f64", "--rate", SignificantDigits(c.recipe.rate_hz, 17), "--units", "rad/s"};
    p->diagnose_args.insert(p->diagnose_args.end(), kIndependentModel.begin(), kIndependentModel.end());
    MaybeReuse(o, p);
    if (p->reusable) return std::nullopt;
    return WriteF64(p->record, independent::Generate(c.recipe, c.num_samples, o.seed, static_cast<std::uint64_t>(i)));
  };
}

// The ADIS16405 gyro axes (deg/s, 100 Hz) cut into segments of `segment_s`.
struct RealSegments {
  std::vector<std::pair<std::string, std::vector<double>>> segments;  // name, rad/s
  double rate_hz = 100.0;
};

std::optional<CommandFailure> LoadRealSegments(const fs::path& dir, double segment_s, RealSegments* out) {
  for (const char* file : {"adis_16405_imu1", "adis_16405_imu2"}) {
    for (const char* axis : {"Gyro_X", "Gyro_Y", "Gyro_Z"}) {
      RecordReaderOptions ro;
      ro.path = (dir / "real" / "adis16405" / (std::string(file) + ".csv.xz")).string();
      ro.column = axis;
      ro.units = "deg/s";  // the ADIS16405 files name no unit; the segments are converted to rad/s below
      std::vector<double> values;
      RecordInfo info;
      RecordError error;
      if (!ReadRecordValues(ro, &values, &info, &error)) return RuntimeFailure(error.message);
      out->rate_hz = info.sample_clock.rate_hz();
      const auto len = static_cast<std::size_t>(std::llround(segment_s * info.sample_clock.rate_hz()));
      for (std::size_t start = 0, k = 0; start + len <= values.size(); start += len, ++k) {
        std::vector<double> seg(values.begin() + static_cast<std::ptrdiff_t>(start),
                                values.begin() + static_cast<std::ptrdiff_t>(start + len));
        for (double& v : seg) v *= M_PI / 180.0;
        std::ostringstream name;
        name << file << ':' << axis << ':' << static_cast<double>(start) / info.sample_clock.rate_hz() << "s";
        out->segments.emplace_back(name.str(), std::move(seg));
      }
    }
  }
  return std::nullopt;
}

PrepareRecording InjectedPreparer(const DiagnosisBenchmarkOptions& o, const RealSegments& real, const fs::path& work) {
  return [&o, &real, work](int i, Prepared* p) -> std::optional<CommandFailure> {
    // Effects in turn; the segments stepped through with a stride coprime to their count.
    const std::size_t n = real.segments.size();
    const auto& [name, segment] = real.segments[(static_cast<std::size_t>(i) * 7) % n];
    IndependentCase c;
    std::vector<double> record;
    std::string why;
    if (!DrawInjectedCase(segment, real.rate_hz, name, o.seed, i, &c, &record, &why)) {
      return RuntimeFailure("injected recording " + std::to_string(i) + ": " + why);
    }
    p->c = c.descriptor;
    SetPaths(work, "real" + std::to_string(i), p);
    p->diagnose_args = {"--format", "f64", "--rate", SignificantDigits(real.rate_hz, 17), "--units", "rad/s"};
    p->diagnose_args.insert(p->diagnose_args.end(), kIndependentModel.begin(), kIndependentModel.end());
    MaybeReuse(o, p);
    if (p->reusable) return std::nullopt;
    return WriteF64(p->record, record);
  };
}

const char* kSimDescription =
    "Each recording is drawn at random (sensor preset reduced to its IEEE 952 terms, length, rate, effect or "
    "none, strength), written as a file by `allanlab simulate`, and diagnosed by `allanlab diagnose` with its "
    "default settings, told nothing but the file's format, rate and unit. Strength is the expected peak gap z of "
    "the view that sees the effect (OAVAR against the best baseline fit; kurtosis for outliers and quantizers; "
    "halves for steps and drifts): see experiments/diagnosis/benchmark_case.h. Classes: weak < 2, borderline < 10, "
    "clear >= 10. Rates carry Wilson 95 % intervals.";

const char* kIndependentDescription =
    "Each recording comes from independent/, a generator written apart from sim/ and from the diagnosis "
    "candidates (continuous-time terms averaged over each sample, flicker by spectral synthesis, four digital "
    "low-pass designs and CIC decimation, Poisson telegraph, heavy-tailed one- and two-sided spikes, quantizers "
    "with random bias and dither, random phases and signs), written as raw float64 and diagnosed by `allanlab "
    "diagnose FILE --format f64 --rate R --units rad/s --model N,B,K` (the user's model: the IEEE terms the "
    "sensor was made with). Controls and effects follow a fixed layout, effects in turn, every fourth round "
    "borderline; strength is the expected gap z computed from the generator's own closed forms (OAVAR against "
    "the user's model refitted; kurtosis for spikes and quantizers; adjacent block means for steps and drifts): "
    "see experiments/diagnosis/independent_case.h. Classes: borderline [3, 10), clear >= 10. Rates carry Wilson "
    "95 % intervals.";

struct Outputs {
  AtomicFile csv, md, png;
};

std::optional<CommandFailure> OpenOutputs(const DiagnosisBenchmarkOptions& o, const fs::path& dir, const std::string& stem,
                                          Outputs* out) {
  std::string why;
  if (!out->csv.Open((dir / (stem + ".csv")).string(), &why)) return RuntimeFailure(why);
  if (!out->md.Open((dir / (stem + ".md")).string(), &why)) return RuntimeFailure(why);
  if (o.plot && !out->png.Open((dir / (stem + ".png")).string(), &why)) return RuntimeFailure(why);
  return std::nullopt;
}

std::string ProvenanceList(const Provenance& p) {
  std::ostringstream list;
  list << "- tool: allanlab " << p.version << " (git " << p.git_sha << ", " << p.build_type << ")\n- date: " << p.utc_date
       << "\n- command: `" << p.command_line << "`\n";
  for (const auto& [k, v] : p.fields) list << "- " << k << ": " << v << "\n";
  return list.str();
}

std::string Cpu(double s) {
  std::ostringstream os;
  os.precision(4);
  os << s << " s (" << s / 60.0 << " min)";
  return os.str();
}

std::optional<CommandFailure> Benchmark(const DiagnosisBenchmarkOptions& o, const std::string& command_line) {
  std::string why;
  if (o.recordings < 1 || o.recordings > 100000) return UsageFailure("--recordings must be in [1, 100000]");
  if (o.jobs < 1 || o.jobs > 64) return UsageFailure("--jobs must be in [1, 64]");
  if (o.generator != "sim" && o.generator != "independent" && o.generator != "both") {
    return UsageFailure("--generator must be sim, independent or both (not '" + o.generator + "')");
  }
  if (o.real_recordings < 0 || o.real_recordings > 10000) return UsageFailure("--real-recordings must be in [0, 10000]");
  const bool run_sim = o.generator != "independent", run_independent = o.generator != "sim";
  BenchmarkDrawOptions draw;
  draw.min_duration_s = o.min_duration_s;
  draw.max_duration_s = o.max_duration_s;
  draw.min_rate_hz = o.min_rate_hz;
  draw.max_rate_hz = o.max_rate_hz;
  draw.max_samples = o.max_samples;
  draw.control_fraction = o.control_fraction;
  if (run_sim && !draw.IsValid(&why)) return UsageFailure(why);
  IndependentDrawOptions idraw;
  idraw.rate_hz = o.independent_rate_hz;
  idraw.min_duration_s = o.independent_min_duration_s;
  idraw.max_duration_s = o.independent_max_duration_s;
  idraw.control_fraction = o.independent_control_fraction;
  {
    Effect resonance;
    idraw.with_resonance = ParseEffect("resonance", &resonance);
  }
  if (run_independent && !idraw.IsValid(&why)) return UsageFailure("independent generator: " + why);
  if (o.plot && !FindGnuplot(&why)) return RuntimeFailure(why + " (or pass --no-plot)");
  const fs::path out_dir(o.out_dir);
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec) return RuntimeFailure("--out-dir " + o.out_dir + ": " + ec.message());
  Outputs sim_out, indep_out;
  AtomicFile timing, comparison;
  if (run_sim) {
    if (auto f = OpenOutputs(o, out_dir, "benchmark", &sim_out)) return f;
  }
  if (run_independent) {
    if (auto f = OpenOutputs(o, out_dir, "benchmark_independent", &indep_out)) return f;
  }
  if (o.generator == "both" && !comparison.Open((out_dir / "benchmark_generators.md").string(), &why)) return RuntimeFailure(why);
  if (!o.timing_path.empty() && !timing.Open(o.timing_path, &why)) return RuntimeFailure(why);
  // The real recordings for the injected cases: skipped, with a message, when the data are absent.
  RealSegments real;
  std::string real_note = "none asked (--real-recordings 0)";
  if (run_independent && o.real_recordings > 0) {
    const fs::path data = o.data_dir.empty() ? fs::path(ALLANLAB_SOURCE_DIR) / ".." / "shared" / "data" : fs::path(o.data_dir);
    if (!fs::exists(data / "real" / "adis16405" / "adis_16405_imu1.csv.xz")) {
      real_note = "skipped: no ADIS16405 recordings under " + data.string() + " (give --data-dir DIR)";
      std::fprintf(stderr, "allanlab %s: real recordings %s\n", kCommand, real_note.c_str());
    } else {
      if (auto f = LoadRealSegments(data, o.real_segment_s, &real)) return f;
      if (real.segments.empty()) return UsageFailure("--real-segment is longer than the recordings");
      real_note = std::to_string(o.real_recordings) + " from " + std::to_string(real.segments.size()) + " segments of " +
                  ShortestDecimal(o.real_segment_s) + " s of the ADIS16405 imu1/imu2 gyro axes in " + data.string();
    }
  }
  fs::path work = o.work_dir.empty()
                      ? fs::temp_directory_path() / ("allanlab_diagnosis_benchmark_" + std::to_string(o.seed) + "_" +
                                                     std::to_string(::getpid()))
                      : fs::path(o.work_dir);
  fs::create_directories(work, ec);
  if (ec) return RuntimeFailure("--work-dir " + work.string() + ": " + ec.message());

  RunResult sim_run, indep_run, real_run;
  if (run_sim) {
    if (auto f = RunRecordings(o, o.recordings, "sim", SimPreparer(o, draw, work), &sim_run)) return f;
  }
  if (run_independent) {
    if (auto f = RunRecordings(o, o.recordings, "independent", IndependentPreparer(o, idraw, work), &indep_run)) return f;
    if (!real.segments.empty()) {
      if (auto f = RunRecordings(o, o.real_recordings, "real+injected", InjectedPreparer(o, real, work), &real_run)) return f;
    }
  }
  if (timing.is_open()) {
    timing.stream() << "generator,index,truth,samples,cpu_s,wall_s\n";
    for (const RunResult* r : {&sim_run, &indep_run, &real_run}) {
      for (const auto& line : r->timing_lines) timing.stream() << line;
    }
  }
  Provenance base = MakeProvenance(kCommand, command_line);
  base.Add("seed", std::to_string(o.seed));
  base.Add("recordings", std::to_string(o.recordings) + " per generator");
  std::vector<std::pair<std::string, BenchmarkSummary>> summaries;
  if (run_sim) {
    const BenchmarkSummary summary = SummarizeBenchmark(sim_run.rows);
    summaries.emplace_back("sim", summary);
    Provenance p = base;
    p.Add("generator", "sim (sim/: simulate --sensor <spec> --seed <seed> --trial <index> --format f64 --units rad/s)");
    p.Add("presets", "consumer_mems, fog, mg25_mems, rlg, tactical_mems, tg100 (IEEE 952 terms only)");
    p.Add("duration", ShortestDecimal(o.min_duration_s) + " .. " + ShortestDecimal(o.max_duration_s) + " s, log-uniform");
    p.Add("rate", ShortestDecimal(o.min_rate_hz) + " .. " + ShortestDecimal(o.max_rate_hz) +
                      " Hz, log-uniform, lowered to keep samples <= " + std::to_string(o.max_samples));
    p.Add("control_fraction", ShortestDecimal(o.control_fraction));
    p.Add("strength_classes", "weak 0.2 (z 0.3..2), borderline 0.2 (2..10), clear 0.6 (10..100), log-uniform targets");
    p.Add("diagnose", "default settings (told the format, rate and unit only)");
    p.Add("diagnose_cpu", Cpu(sim_run.cpu_s) + " over the recordings diagnosed in this run");
    if (o.reuse) p.Add("reused_diagnoses", std::to_string(sim_run.reused) + " from the work directory (each JSON names the build that made it)");
    WriteBenchmarkCsv(sim_out.csv.stream(), ProvenanceCommentLines(p), sim_run.rows);
    WriteBenchmarkMarkdown(sim_out.md.stream(), "Blind diagnosis benchmark: sim generator", kSimDescription,
                           ProvenanceList(p), sim_run.rows, summary);
    if (o.plot && !RenderAllanPlot(RatePlot(summary, o.seed, o.recordings), &sim_out.png, &why)) return RuntimeFailure(why);
  }
  if (run_independent) {
    const BenchmarkSummary summary = SummarizeBenchmark(indep_run.rows);
    summaries.emplace_back("independent", summary);
    Provenance p = base;
    p.Add("generator", "independent (independent/: Generate(recipe, n, seed, index), raw float64 rad/s)");
    p.Add("sensor", "N 0.05..0.5 deg/sqrt(h), flicker floor 0.5..10 deg/h, K 0.5..10 deg/h/sqrt(h), bias +-0.05..1 deg/s, all log-uniform");
    p.Add("duration", ShortestDecimal(o.independent_min_duration_s) + " .. " + ShortestDecimal(o.independent_max_duration_s) +
                          " s, log-uniform, at " + ShortestDecimal(o.independent_rate_hz) + " Hz");
    p.Add("control_fraction", ShortestDecimal(o.independent_control_fraction) + " (evenly spread)");
    p.Add("effects", std::string("in turn: ") + [&] {
            std::string s;
            for (const auto& id : IndependentEffectOrder(idraw.with_resonance)) s += (s.empty() ? "" : ", ") + id;
            return s;
          }() + "; every fourth round borderline (z 3..10), the others clear (z 10..60)");
    p.Add("diagnose", "--model N,B,K (the user's model), otherwise default settings");
    p.Add("real_recordings", real_note);
    p.Add("diagnose_cpu", Cpu(indep_run.cpu_s + real_run.cpu_s) + " over the recordings diagnosed in this run");
    if (o.reuse) p.Add("reused_diagnoses", std::to_string(indep_run.reused + real_run.reused) + " from the work directory");
    std::vector<BenchmarkRow> all = indep_run.rows;
    WriteBenchmarkCsv(indep_out.csv.stream(), ProvenanceCommentLines(p), all);
    std::ostringstream md;
    WriteBenchmarkMarkdown(md, "Diagnosis benchmark: independent generator", kIndependentDescription, ProvenanceList(p),
                           indep_run.rows, summary);
    // The injected real recordings go before the provenance.
    std::string text = md.str();
    std::ostringstream injected;
    if (!real.segments.empty()) {
      WriteInjectedSection(injected, real_run.rows);
    } else {
      injected << "## Real recordings with an injected effect\n\n" << real_note << ".\n\n";
    }
    const std::size_t at = text.rfind("## Provenance");
    text.insert(at == std::string::npos ? text.size() : at, injected.str());
    indep_out.md.stream() << text;
    if (o.plot && !RenderAllanPlot(RatePlot(summary, o.seed, o.recordings), &indep_out.png, &why)) return RuntimeFailure(why);
  }
  if (comparison.is_open()) WriteGeneratorComparison(comparison.stream(), ProvenanceList(base), summaries);
  for (AtomicFile* f : {&sim_out.csv, &sim_out.md, &sim_out.png, &indep_out.csv, &indep_out.md, &indep_out.png,
                        &comparison, &timing}) {
    if (f->is_open() && !f->Commit(&why)) return RuntimeFailure(why);
  }
  if (o.work_dir.empty() && !o.keep_work) fs::remove_all(work, ec);
  for (const auto& [name, s] : summaries) {
    std::cout << name << ": false alarms on controls: " << s.false_alarm.successes << "/" << s.false_alarm.trials
              << "; right effect on clear single effects: " << s.clear_right.successes << "/" << s.clear_right.trials
              << "; held-out shrink >= 5x: " << s.shrink_5x.successes << "/" << s.shrink_count << "\n";
  }
  return std::nullopt;
}

}  // namespace

Subcommand AddDiagnosisBenchmarkCommand(CLI::App* parent) {
  auto o = std::make_shared<DiagnosisBenchmarkOptions>();
  CLI::App* cmd = parent->add_subcommand(
      kCommand,
      "Blind benchmark of diagnose: random recordings (preset, length, rate, effect or none, strength) written "
      "as files, diagnosed without being told the effect, scored (confusion matrix, detection vs strength, "
      "false alarms, localization, held-out shrinkage).");
  cmd->add_option("--recordings", o->recordings, "number of recordings (default 80)")->type_name("N");
  cmd->add_option("--seed", o->seed, "seed of the draw and of the records (default 1)")->type_name("N");
  cmd->add_option("--out-dir", o->out_dir, "where benchmark.csv, .md and .png go (default results/diagnosis/benchmark)")->type_name("DIR");
  cmd->add_option("--work-dir", o->work_dir, "where specs, records and diagnoses go (default: a temp directory)")->type_name("DIR");
  cmd->add_flag("--keep-work", o->keep_work, "keep the records (default: deleted once diagnosed)");
  cmd->add_option("--max-samples", o->max_samples, "cap on samples per record (default 1080000)")->type_name("N");
  cmd->add_option("--min-duration", o->min_duration_s, "shortest record [s] (default 1800)")->type_name("S");
  cmd->add_option("--max-duration", o->max_duration_s, "longest record [s] (default 10800)")->type_name("S");
  cmd->add_option("--min-rate", o->min_rate_hz, "lowest rate [Hz] (default 100)")->type_name("HZ");
  cmd->add_option("--max-rate", o->max_rate_hz, "highest rate [Hz] (default 1000)")->type_name("HZ");
  cmd->add_option("--control-fraction", o->control_fraction, "share of recordings with no effect (default 0.4)")->type_name("P");
  cmd->add_option("--generator", o->generator,
                  "sim (sim/'s generators, default), independent (independent/, written apart from sim/ and the "
                  "diagnosis), or both side by side")->type_name("sim|independent|both");
  cmd->add_option("--independent-rate", o->independent_rate_hz, "independent generator: rate [Hz] (default 100)")->type_name("HZ");
  cmd->add_option("--independent-min-duration", o->independent_min_duration_s, "independent generator: shortest record [s] (default 1800)")->type_name("S");
  cmd->add_option("--independent-max-duration", o->independent_max_duration_s, "independent generator: longest record [s] (default 3600)")->type_name("S");
  cmd->add_option("--independent-control-fraction", o->independent_control_fraction,
                  "independent generator: share of controls (default 0.45)")->type_name("P");
  cmd->add_option("--real-recordings", o->real_recordings,
                  "independent generator: ADIS16405 segments with an injected effect (default 0)")->type_name("N");
  cmd->add_option("--real-segment", o->real_segment_s, "length of those segments [s] (default 1800)")->type_name("S");
  cmd->add_option("--data-dir", o->data_dir, "where real/adis16405 is (default ../shared/data beside the repository)")->type_name("DIR");
  cmd->add_option("--jobs", o->jobs, "diagnoses run at once, as child processes (default 2)")->type_name("N");
  cmd->add_flag("--reuse", o->reuse, "reuse diagnoses an earlier run of the same draw left in --work-dir");
  cmd->add_option("--timing", o->timing_path, "per-recording CPU and wall seconds (CSV)")->type_name("FILE");
  cmd->add_flag_callback("--no-plot", [o] { o->plot = false; }, "no PNG");
  return {cmd, [o](const std::string& command_line) { return RunDiagnosisBenchmark(*o, command_line); }};
}

int RunDiagnosisBenchmark(const DiagnosisBenchmarkOptions& options, const std::string& command_line) {
  return RunCommand(kCommand, "", [&] { return Benchmark(options, command_line); });
}

}  // namespace allanlab::app
