#pragma once
// `allanlab diagnosis-benchmark`: the blind benchmark of `allanlab diagnose` ("Proof on
// data whose effect is withheld"). From --seed, --recordings cases are drawn
// (experiments/diagnosis/benchmark_case.h: preset, length, rate, effect or none, strength); each is
// written as a sensor spec (the preset's IEEE 952 terms plus the effect) and a raw f64 record by
// `simulate`'s own code (app/reports/simulated_record.h), diagnosed by the CLI itself (a child process `allanlab
// diagnose FILE --format f64 --rate R --units rad/s --json OUT`: default settings, told only the
// file's format, rate and unit), its JSON read back and scored
// (benchmark_score.h). Writes <out-dir>/benchmark.csv, benchmark.md (benchmark_report.h) and
// benchmark.png (detection and right-effect rate vs strength), with provenance.
//   --recordings N      (default 80)    --seed S (default 1)
//   --out-dir DIR       (default results/diagnosis/benchmark)
//   --work-dir DIR      where the specs, records and diagnoses go (default: a fresh directory in
//                       the system temp dir); records are deleted once diagnosed unless --keep-work
//   --max-samples N     cap on samples per record (default 1080000; the rate is lowered to fit)
//   --min-duration S --max-duration S --min-rate HZ --max-rate HZ   (defaults 1800, 10800, 100, 1000)
//   --control-fraction F (default 0.4)
//   --reuse             a recording whose diagnosis JSON an earlier run of the same draw left in
//                       --work-dir (same record path and sample count) is scored from it, not rerun
//   --jobs J            diagnoses at once (default 2; each is a process)
//   --timing FILE       per-recording CPU (user + sys) and wall seconds, CSV (not deterministic, so
//                       kept out of the tables)
//   --generator G       sim (default): the draw above; independent: recordings from independent/
//                       (experiments/diagnosis/independent_case.h), written as raw f64 and diagnosed
//                       with --model N,B,K, to <out-dir>/benchmark_independent.{csv,md,png}; both: the
//                       two, and <out-dir>/benchmark_generators.md with their targets side by side
//   --independent-rate HZ --independent-min-duration S --independent-max-duration S
//   --independent-control-fraction F   (defaults 100, 1800, 3600, 0.45)
//   --real-recordings K ADIS16405 gyro segments (--real-segment S long, default 1800) with one
//                       injected effect each, in the independent table (default 0); skipped with a
//                       message when --data-dir DIR (default ../shared/data beside the repository)
//                       has no real/adis16405 recordings
// Deterministic: the tables depend on the seed and options only (diagnose is deterministic for any
// thread count). Exit codes: 2 usage, 1 a recording could not be written or an output not
// written (a diagnose failure on a record is a row, not an error), 0 otherwise.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>

#include "app/commands/subcommand.h"

namespace allanlab::app {

struct DiagnosisBenchmarkOptions {
  int recordings = 80;
  std::uint64_t seed = 1;
  std::string out_dir = "results/diagnosis/benchmark";
  std::string work_dir;
  bool keep_work = false;
  std::int64_t max_samples = 1080000;
  double min_duration_s = 1800.0, max_duration_s = 10800.0;
  double min_rate_hz = 100.0, max_rate_hz = 1000.0;
  double control_fraction = 0.4;
  int jobs = 2;
  bool reuse = false;
  std::string timing_path;
  bool plot = true;  // --no-plot: no PNG (machines without gnuplot)
  std::string generator = "sim";  // sim | independent | both
  double independent_rate_hz = 100.0;
  double independent_min_duration_s = 1800.0, independent_max_duration_s = 3600.0;
  double independent_control_fraction = 0.45;
  int real_recordings = 0;       // ADIS16405 segments with an injected effect (independent generator)
  double real_segment_s = 1800.0;
  std::string data_dir;          // empty: <source dir>/../shared/data
};

Subcommand AddDiagnosisBenchmarkCommand(CLI::App* parent);
int RunDiagnosisBenchmark(const DiagnosisBenchmarkOptions& options, const std::string& command_line);

}  // namespace allanlab::app
