// Monte Carlo throughput of the sweep engine (the runner's speed target): MG-25 preset at 200 Hz, 1 h
// records, per trial the octave overlapping Allan curve and a GLS fit of Q, N, B, K, R.
// Measures (1) the bare loop generate + estimate + fit on one thread, (2) RunSweep on 1 and 2
// threads with the same work in a TrialDriver: trials/s, scaling efficiency and the engine's
// overhead over the bare loop. Wall and CPU time both printed (the machine may be shared).
// Usage: experiments_bench [TRIALS (default 16)]
#include <time.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "estimators/allan_family.h"
#include "estimators/fit/fit_avar_model.h"
#include "experiments/runner.h"
#include "experiments/sweep_spec.h"
#include "experiments/trial_driver.h"

namespace {

using namespace allanlab;

double Now(clockid_t clock) {
  timespec ts;
  clock_gettime(clock, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

struct Workspace : experiments::TrialWorkspace {
  estimators::AllanFamilyWorkspace allan;
};

// One trial: record, octave OAVAR, GLS fit. Returns the five fitted coefficients.
std::vector<double> Trial(const experiments::SweepPoint& point, std::uint64_t seed,
                          std::int64_t trial, Workspace* w) {
  const std::vector<double> rate =
      point.model.Generate(seed, static_cast<std::uint64_t>(trial), point.num_samples);
  estimators::AvarOptions options;
  options.statistic = estimators::Statistic::kAllanOverlapping;
  options.sample_clock = point.model.sample_clock;
  options.confidence_method = estimators::ConfidenceMethod::kNone;
  estimators::AvarSummary summary;
  if (!estimators::ComputeStatisticValues(options, rate, &summary, &w->allan)) {
    throw std::runtime_error(summary.message);
  }
  estimators::AvarCurve curve;
  curve.sample_clock = options.sample_clock;
  curve.num_samples = point.num_samples;
  for (const estimators::AvarPoint& p : summary.points) {
    curve.m.push_back(p.m);
    curve.tau_s.push_back(p.tau_s);
    curve.avar.push_back(p.value);
  }
  estimators::FitOptions fit;
  fit.method = estimators::FitMethod::kGls;
  estimators::FitSummary result;
  if (!estimators::FitAvarModel(fit, curve, &result)) throw std::runtime_error(result.message);
  std::vector<double> out;
  for (const auto& c : result.coefficients) out.push_back(c.value_si);
  return out;
}

class FitDriver : public experiments::TrialDriver {
 public:
  std::vector<std::string> Columns(const experiments::SweepSpec&,
                                   const experiments::SweepPoint&) const override {
    return {"Q", "N", "B", "K", "R"};
  }
  std::unique_ptr<experiments::TrialWorkspace> MakeWorkspace() const override {
    return std::make_unique<Workspace>();
  }
  std::vector<double> Run(const experiments::SweepSpec& spec, const experiments::SweepPoint& point,
                          std::int64_t trial, experiments::TrialWorkspace* w) const override {
    const double start = Now(CLOCK_THREAD_CPUTIME_ID);
    std::vector<double> out = Trial(point, experiments::PointSeed(spec.seed, point.index), trial,
                                    static_cast<Workspace*>(w));
    trial_cpu_s.fetch_add(Now(CLOCK_THREAD_CPUTIME_ID) - start);
    return out;
  }
  // CPU seconds spent inside the trials themselves, summed over threads: what the engine adds is
  // the process CPU time minus this, measured in the same run (free of run-to-run machine noise).
  mutable std::atomic<double> trial_cpu_s{0.0};
};

}  // namespace

int main(int argc, char** argv) {
  const int trials = argc > 1 ? std::atoi(argv[1]) : 16;
  const std::string yaml = "name: bench\ndriver: avar_bias\nseed: 1\ntrials: " +
                           std::to_string(trials) +
                           "\nsensor: {preset: mg25_mems}\nrecord: {duration: 1 h, sample_rate: 200 Hz}\n";
  experiments::SweepSpec spec;
  std::string why;
  if (!experiments::LoadSweepSpecYaml(yaml, "bench", &spec, &why)) {
    std::fprintf(stderr, "%s\n", why.c_str());
    return 1;
  }
  const experiments::SweepPoint& point = spec.points[0];
  std::printf("MG-25 preset, %lld samples (1 h at %g Hz), OAVAR octave + GLS (Q,N,B,K,R), %d trials\n",
              static_cast<long long>(point.num_samples), point.model.sample_clock.rate_hz(), trials);

  // Bare loop, one thread, after one untimed trial (page faults of the first buffers, Ceres set-up).
  Workspace w;
  Trial(point, experiments::PointSeed(spec.seed, 0), trials, &w);
  double wall = Now(CLOCK_MONOTONIC), cpu = Now(CLOCK_PROCESS_CPUTIME_ID);
  double checksum = 0.0;
  for (int t = 0; t < trials; ++t) checksum += Trial(point, experiments::PointSeed(spec.seed, 0), t, &w)[1];
  const double bare_wall = Now(CLOCK_MONOTONIC) - wall;
  const double bare_cpu = Now(CLOCK_PROCESS_CPUTIME_ID) - cpu;
  std::printf("bare loop, 1 thread : %7.3f trials/s wall, %7.3f trials/s CPU (checksum %.6g)\n",
              trials / bare_wall, trials / bare_cpu, checksum);

  FitDriver driver;
  double rate[3] = {0, 0, 0};
  double cpu_rate[3] = {0, 0, 0};
  double engine_share[3] = {0, 0, 0};
  for (int threads : {1, 2}) {
    driver.trial_cpu_s = 0.0;
    experiments::RunnerOptions options;
    options.threads = threads;
    options.batch_trials = 4;
    experiments::RunSummary run;
    wall = Now(CLOCK_MONOTONIC);
    cpu = Now(CLOCK_PROCESS_CPUTIME_ID);
    if (!experiments::RunSweep(spec, driver, options, &run) || run.trials_failed > 0) {
      std::fprintf(stderr, "sweep failed: %s\n", run.message.c_str());
      return 1;
    }
    const double t_wall = Now(CLOCK_MONOTONIC) - wall;
    const double t_cpu = Now(CLOCK_PROCESS_CPUTIME_ID) - cpu;
    engine_share[threads] = (t_cpu - driver.trial_cpu_s.load()) / driver.trial_cpu_s.load();
    rate[threads] = trials / t_wall;
    cpu_rate[threads] = trials / t_cpu;
    std::printf("RunSweep, %d thread%s: %7.3f trials/s wall, %7.3f trials/s per CPU-second\n", threads,
                threads == 1 ? " " : "s", rate[threads], cpu_rate[threads]);
  }
  // The bare loop again: the machine may be shared, so the two bare runs bracket the sweeps.
  wall = Now(CLOCK_MONOTONIC);
  cpu = Now(CLOCK_PROCESS_CPUTIME_ID);
  for (int t = 0; t < trials; ++t) checksum += Trial(point, experiments::PointSeed(spec.seed, 0), t, &w)[1];
  const double bare_wall2 = Now(CLOCK_MONOTONIC) - wall;
  const double bare_cpu2 = Now(CLOCK_PROCESS_CPUTIME_ID) - cpu;
  std::printf("bare loop again     : %7.3f trials/s wall, %7.3f trials/s CPU\n", trials / bare_wall2,
              trials / bare_cpu2);
  std::printf("engine overhead vs the second bare loop: %+.1f %% wall, %+.1f %% CPU\n",
              100.0 * (trials / rate[1] - bare_wall2) / bare_wall2,
              100.0 * (trials / cpu_rate[1] - bare_cpu2) / bare_cpu2);
  std::printf("engine overhead, 1 thread: %+.1f %% wall, %+.1f %% CPU (target <= 5 %%)\n",
              100.0 * (trials / rate[1] - bare_wall) / bare_wall,
              100.0 * (trials / cpu_rate[1] - bare_cpu) / bare_cpu);
  std::printf("engine's own CPU time (process CPU outside Trial / CPU inside Trial): %+.2f %% on 1 thread, "
              "%+.2f %% on 2 threads (target <= 5 %%)\n",
              100.0 * engine_share[1], 100.0 * engine_share[2]);
  std::printf("scaling efficiency, 2 threads: %.1f %% wall (target >= 85 %%), %.1f %% CPU-time ratio\n",
              100.0 * rate[2] / (2.0 * rate[1]), 100.0 * cpu_rate[2] / cpu_rate[1]);
  return 0;
}
