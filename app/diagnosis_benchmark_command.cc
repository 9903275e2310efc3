#include "app/diagnosis_benchmark_command.h"

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
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/allan_plot.h"
#include "app/atomic_file.h"
#include "app/provenance.h"
#include "app/simulate_command.h"
#include "experiments/diagnosis/benchmark_case.h"
#include "experiments/diagnosis/benchmark_report.h"
#include "experiments/diagnosis/benchmark_score.h"
#include "sim/embedded_presets.h"
#include "sim/sensor_spec.h"

namespace allanlab::app {
namespace {

constexpr const char* kCommand = "diagnosis-benchmark";
namespace fs = std::filesystem;
using namespace allanlab::experiments;

std::string Exact(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

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
        extra << "band_limit: {type: " << (p.at("order") == 2.0 ? "butterworth2" : "first_order")
              << ", cutoff: " << Exact(p.at("cutoff_hz")) << " Hz, oversampling: " << c.model.band_limit.oversampling
              << ", sampling: point}\n";
        break;
      case Effect::kAngleQuantization:
        extra << "output: {angle_lsb: " << Exact(p.at("lsb_rad")) << " rad}\n";
        break;
      case Effect::kRateQuantization:
        extra << "output: {rate_lsb: " << Exact(p.at("lsb_rad_per_s")) << " rad/s}\n";
        break;
      case Effect::kGaussMarkov:
        term << "  - {type: gauss_markov, sigma: " << Exact(p.at("sigma_rad_per_s")) << " rad/s, correlation_time: "
             << Exact(p.at("correlation_time_s")) << " s}";
        break;
      case Effect::kRandomTelegraph:
        term << "  - {type: random_telegraph, amplitude: " << Exact(p.at("amplitude_rad_per_s"))
             << " rad/s, mean_dwell: " << Exact(p.at("mean_dwell_s")) << " s}";
        break;
      case Effect::kHarmonic:
        term << "  - {type: harmonic, amplitude: " << Exact(p.at("amplitude_rad_per_s")) << " rad/s, frequency: "
             << Exact(p.at("frequency_hz")) << " Hz}";
        break;
      case Effect::kExponentialDrift:
        term << "  - {type: exponential_drift, amplitude: " << Exact(p.at("amplitude_rad_per_s"))
             << " rad/s, time_constant: " << Exact(p.at("time_constant_s")) << " s}";
        break;
      case Effect::kBiasStep:
        term << "  - {type: bias_step, size: " << Exact(p.at("size_rad_per_s")) << " rad/s, time: "
             << Exact(p.at("time_s")) << " s}";
        break;
      case Effect::kOutliers:
        term << "  - {type: outliers, rate: " << Exact(p.at("rate_hz")) << " Hz, size: "
             << Exact(p.at("size_rad_per_s")) << " rad/s}";
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
  loaded.sample_rate_hz = c.rate_hz;
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

// Detection and right-effect rates per strength bin, with their intervals, on log axes.
AllanPlot RatePlot(const BenchmarkSummary& s, std::uint64_t seed, int recordings) {
  AllanPlot plot;
  std::ostringstream title;
  title << "allanlab diagnosis-benchmark: " << recordings << " recordings, seed " << seed
        << " (bins with rate 0 not drawn)";
  plot.title = title.str();
  plot.x_label = "strength: expected peak gap z";
  plot.y_label = "rate";
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

std::optional<CommandFailure> Benchmark(const DiagnosisBenchmarkOptions& o, const std::string& command_line) {
  std::string why;
  if (o.recordings < 1 || o.recordings > 100000) return UsageFailure("--recordings must be in [1, 100000]");
  if (o.jobs < 1 || o.jobs > 64) return UsageFailure("--jobs must be in [1, 64]");
  BenchmarkDrawOptions draw;
  draw.min_duration_s = o.min_duration_s;
  draw.max_duration_s = o.max_duration_s;
  draw.min_rate_hz = o.min_rate_hz;
  draw.max_rate_hz = o.max_rate_hz;
  draw.max_samples = o.max_samples;
  draw.control_fraction = o.control_fraction;
  if (!draw.IsValid(&why)) return UsageFailure(why);
  if (o.plot && !FindGnuplot(&why)) return RuntimeFailure(why + " (or pass --no-plot)");
  const fs::path out_dir(o.out_dir);
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec) return RuntimeFailure("--out-dir " + o.out_dir + ": " + ec.message());
  AtomicFile csv, md, png, timing;
  if (!csv.Open((out_dir / "benchmark.csv").string(), &why)) return RuntimeFailure(why);
  if (!md.Open((out_dir / "benchmark.md").string(), &why)) return RuntimeFailure(why);
  if (o.plot && !png.Open((out_dir / "benchmark.png").string(), &why)) return RuntimeFailure(why);
  if (!o.timing_path.empty() && !timing.Open(o.timing_path, &why)) return RuntimeFailure(why);
  fs::path work = o.work_dir.empty()
                      ? fs::temp_directory_path() / ("allanlab_diagnosis_benchmark_" + std::to_string(o.seed) + "_" +
                                                     std::to_string(::getpid()))
                      : fs::path(o.work_dir);
  fs::create_directories(work, ec);
  if (ec) return RuntimeFailure("--work-dir " + work.string() + ": " + ec.message());

  // Diagnoses run as child processes of this very binary (`allanlab diagnose FILE ...`, the CLI
  // itself), up to --jobs at a time, while the next recordings are drawn and written.
  const std::string self = fs::read_symlink("/proc/self/exe", ec).string();
  if (ec) return RuntimeFailure("cannot find the allanlab binary (/proc/self/exe): " + ec.message());
  struct Running {
    BenchmarkCase c;
    fs::path record, json, log;
    std::chrono::steady_clock::time_point start;
  };
  std::map<pid_t, Running> running;
  std::vector<BenchmarkRow> rows(static_cast<std::size_t>(o.recordings));
  std::vector<std::string> timing_lines(static_cast<std::size_t>(o.recordings));
  int done = 0, reused = 0;
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
    BenchmarkOutcome outcome;
    if (WIFEXITED(status) && WEXITSTATUS(status) == kExitOk) {
      outcome = ReadOutcome(r.json.string());
    } else {
      std::ifstream log(r.log);
      std::string last, line;
      while (std::getline(log, line)) last = line;
      outcome.failure = "diagnose failed: " + last;
    }
    const int i = r.c.index;
    rows[static_cast<std::size_t>(i)] = ScoreBenchmarkCase(r.c, outcome);
    const BenchmarkRow& row = rows[static_cast<std::size_t>(i)];
    ++done;
    std::fprintf(stderr, "allanlab %s: %d/%d done: #%d %s %s N=%lld strength %.3g (%s) -> %s%s (%.1f s CPU, %.1f s wall)\n",
                 kCommand, done, o.recordings, i, r.c.preset.c_str(), row.truth.c_str(),
                 static_cast<long long>(r.c.num_samples), r.c.strength_z, r.c.strength_class.c_str(),
                 outcome.ok ? outcome.verdict.c_str() : outcome.failure.c_str(), row.right ? " [right]" : "", cpu, wall);
    std::ostringstream t;
    t << i << ',' << row.truth << ',' << r.c.num_samples << ',' << cpu << ',' << wall << '\n';
    timing_lines[static_cast<std::size_t>(i)] = t.str();
    if (!o.keep_work) {
      fs::remove(r.record, ec);
      fs::remove(r.record.string() + ".json", ec);
    }
    running.erase(it);
    return std::nullopt;
  };
  for (int i = 0; i < o.recordings; ++i) {
    Running r;
    if (!DrawBenchmarkCase(draw, o.seed, i, &r.c, &why)) return RuntimeFailure("recording " + std::to_string(i) + ": " + why);
    const std::string stem = "rec" + std::to_string(i);
    const fs::path spec = work / (stem + ".yaml");
    r.record = work / (stem + ".f64");
    r.json = work / (stem + ".diagnosis.json");
    r.log = work / (stem + ".diagnose.log");
    std::string yaml;
    if (!SpecYaml(r.c, &yaml, &why)) return RuntimeFailure(why);
    if (o.reuse && fs::exists(r.json)) {
      // A diagnosis an earlier run left for this very recording (same draw: same seed and
      // options; checked by the record path and sample count it names).
      BenchmarkOutcome outcome = ReadOutcome(r.json.string());
      std::ifstream in(r.json);
      nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
      const bool same = !j.is_discarded() && j.contains("provenance") &&
                        j["provenance"].value("input", "") == r.record.string() &&
                        j["provenance"].value("samples", "") == std::to_string(r.c.num_samples);
      if (outcome.ok && same) {
        rows[static_cast<std::size_t>(i)] = ScoreBenchmarkCase(r.c, outcome);
        ++reused;
        ++done;
        std::fprintf(stderr, "allanlab %s: %d/%d reused: #%d %s -> %s\n", kCommand, done, o.recordings, i,
                     rows[static_cast<std::size_t>(i)].truth.c_str(), outcome.verdict.c_str());
        continue;
      }
    }
    {
      std::ofstream out(spec);
      out << yaml;
      if (!out) return RuntimeFailure(spec.string() + ": cannot write");
    }
    SimulateOptions so;
    so.sensor_path = spec.string();
    so.rate_hz = r.c.rate_hz;
    so.duration_s = r.c.duration_s();
    so.seed = o.seed;
    so.trial = static_cast<std::uint64_t>(i);
    so.output_path = r.record.string();
    so.format = "f64";
    so.units = "rad/s";
    std::ostringstream sim_line;
    sim_line << "allanlab simulate --sensor " << spec.string() << " --rate " << Exact(r.c.rate_hz) << " --duration "
             << Exact(so.duration_s) << " --seed " << o.seed << " --trial " << i << " --format f64 --units rad/s -o "
             << r.record.string();
    if (RunSimulate(so, sim_line.str()) != kExitOk) return RuntimeFailure("recording " + std::to_string(i) + ": simulate failed");
    while (static_cast<int>(running.size()) >= o.jobs) {
      if (auto f = reap()) return f;
    }
    std::vector<std::string> args = {self, "diagnose", r.record.string(), "--format", "f64", "--rate",
                                     Exact(r.c.rate_hz), "--units", "rad/s", "--json", r.json.string()};
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, r.log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    pid_t pid = 0;
    r.start = std::chrono::steady_clock::now();
    const int err = posix_spawn(&pid, self.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (err != 0) return RuntimeFailure("cannot start diagnose: " + std::string(std::strerror(err)));
    running.emplace(pid, std::move(r));
  }
  while (!running.empty()) {
    if (auto f = reap()) return f;
  }
  if (timing.is_open()) {
    timing.stream() << "index,truth,samples,cpu_s,wall_s\n";
    for (const auto& line : timing_lines) timing.stream() << line;
  }
  const BenchmarkSummary summary = SummarizeBenchmark(rows);

  Provenance p = MakeProvenance(kCommand, command_line);
  p.Add("seed", std::to_string(o.seed));
  p.Add("recordings", std::to_string(o.recordings));
  p.Add("presets", "consumer_mems, fog, mg25_mems, rlg, tactical_mems, tg100 (IEEE 952 terms only)");
  p.Add("duration", ShortestDecimal(o.min_duration_s) + " .. " + ShortestDecimal(o.max_duration_s) + " s, log-uniform");
  p.Add("rate", ShortestDecimal(o.min_rate_hz) + " .. " + ShortestDecimal(o.max_rate_hz) +
                    " Hz, log-uniform, lowered to keep samples <= " + std::to_string(o.max_samples));
  p.Add("control_fraction", ShortestDecimal(o.control_fraction));
  p.Add("strength_classes", "weak 0.2 (z 0.3..2), borderline 0.2 (2..10), clear 0.6 (10..100), log-uniform targets");
  p.Add("diagnose", "default settings: --model Q,N,B,K,R --trials 30 --seed 1 --false-alarm 0.05");
  p.Add("records", "simulate --seed <seed> --trial <index> --format f64 --units rad/s");
  if (o.reuse) p.Add("reused_diagnoses", std::to_string(reused) + " from the work directory (each JSON names the build that made it)");
  const std::string comments = ProvenanceCommentLines(p);
  std::ostringstream list;
  list << "- tool: allanlab " << p.version << " (git " << p.git_sha << ", " << p.build_type << ")\n- date: " << p.utc_date
       << "\n- command: `" << p.command_line << "`\n";
  for (const auto& [k, v] : p.fields) list << "- " << k << ": " << v << "\n";
  WriteBenchmarkCsv(csv.stream(), comments, rows);
  WriteBenchmarkMarkdown(md.stream(), list.str(), rows, summary);
  if (o.plot && !RenderAllanPlot(RatePlot(summary, o.seed, o.recordings), &png, &why)) return RuntimeFailure(why);
  for (AtomicFile* f : {&csv, &md, &png, &timing}) {
    if (f->is_open() && !f->Commit(&why)) return RuntimeFailure(why);
  }
  if (o.work_dir.empty() && !o.keep_work) fs::remove_all(work, ec);
  std::cout << "false alarms on controls: " << summary.false_alarm.successes << "/" << summary.false_alarm.trials
            << "; right effect on clear single effects: " << summary.clear_right.successes << "/"
            << summary.clear_right.trials << "; held-out shrink >= 5x: " << summary.shrink_5x.successes << "/"
            << summary.shrink_count << "\n";
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
  cmd->add_option("--recordings", o->recordings, "number of recordings (default 80)");
  cmd->add_option("--seed", o->seed, "seed of the draw and of the records (default 1)");
  cmd->add_option("--out-dir", o->out_dir, "where benchmark.csv, .md and .png go (default results/diagnosis)");
  cmd->add_option("--work-dir", o->work_dir, "where specs, records and diagnoses go (default: a temp directory)");
  cmd->add_flag("--keep-work", o->keep_work, "keep the records (default: deleted once diagnosed)");
  cmd->add_option("--max-samples", o->max_samples, "cap on samples per record (default 1080000)");
  cmd->add_option("--min-duration", o->min_duration_s, "shortest record [s] (default 1800)");
  cmd->add_option("--max-duration", o->max_duration_s, "longest record [s] (default 10800)");
  cmd->add_option("--min-rate", o->min_rate_hz, "lowest rate [Hz] (default 100)");
  cmd->add_option("--max-rate", o->max_rate_hz, "highest rate [Hz] (default 1000)");
  cmd->add_option("--control-fraction", o->control_fraction, "share of recordings with no effect (default 0.4)");
  cmd->add_option("--jobs", o->jobs, "diagnoses run at once, as child processes (default 2)");
  cmd->add_flag("--reuse", o->reuse, "reuse diagnoses an earlier run of the same draw left in --work-dir");
  cmd->add_option("--timing", o->timing_path, "per-recording CPU and wall seconds (CSV)")->type_name("FILE");
  cmd->add_flag("!--no-plot", o->plot, "no PNG");
  return {cmd, [o](const std::string& command_line) { return RunDiagnosisBenchmark(*o, command_line); }};
}

int RunDiagnosisBenchmark(const DiagnosisBenchmarkOptions& options, const std::string& command_line) {
  return RunCommand(kCommand, "", [&] { return Benchmark(options, command_line); });
}

}  // namespace allanlab::app
