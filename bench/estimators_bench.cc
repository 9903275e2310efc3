// Allan-family throughput (ns per input sample, one core, double) for whole curves as
// ComputeStatisticValues computes them: mean, phase, all taus of the grid.
// Run: build/bench/estimators_bench --benchmark_counters_tabular=true (scripts/bench-estimators).
// Issue targets: octave OAVAR <= 8 ns/sample at N = 1e7 and 1e8; OAVAR with 10 taus per decade
// <= 25 ns/sample at N = 1e7. "warm" reuses one AllanFamilyWorkspace (a Monte Carlo loop);
// "cold" passes none (a one-off call): OAVAR then keeps no phase and rebuilds it in cache, so it
// touches no record-sized fresh memory.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <map>
#include <vector>

#include "estimators/allan_family.h"
#include "estimators/allan_variance.h"
#include "estimators/difference_kernel.h"
#include "sim/seeding.h"
#include "sim/white_rate_noise.h"

namespace allanlab::estimators {
namespace {

// White rate noise plus a bias, generated once per length and shared by the benchmarks.
const std::vector<double>& Record(std::int64_t n) {
  static std::map<std::int64_t, std::vector<double>> records;
  std::vector<double>& y = records[n];
  if (y.empty()) {
    y.assign(static_cast<std::size_t>(n), 0.01);
    sim::Engine engine = sim::MakeEngine(7, 0, 0);
    sim::WhiteRateNoise{1e-4}.AddTo(engine, 0.005, y);
  }
  return y;
}

void SetCounters(benchmark::State& state, std::int64_t n, std::size_t taus) {
  state.SetItemsProcessed(state.iterations() * n);
  // Seconds per input sample, printed with an SI prefix ("5.2n" = 5.2 ns per sample).
  state.counters["s_per_sample"] =
      benchmark::Counter(static_cast<double>(state.iterations() * n),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["taus"] = static_cast<double>(taus);
  state.SetLabel(DifferenceKernelName());
}

void RunCurve(benchmark::State& state, Statistic statistic, TauGridOptions grid, bool warm) {
  const std::int64_t n = state.range(0);
  const std::vector<double>& y = Record(n);
  AvarOptions options;
  options.statistic = statistic;
  options.taus = grid;
  options.sample_clock = SampleClock::FromPeriodS(0.005);
  AllanFamilyWorkspace workspace;
  AvarSummary summary;
  // Warm: the work space has its pages before the clock starts, as in a long Monte Carlo loop.
  if (warm) ComputeStatisticValues(options, y, &summary, &workspace);
  for (auto _ : state) {
    if (warm) {
      ComputeStatisticValues(options, y, &summary, &workspace);
    } else {
      ComputeStatisticValues(options, y, &summary);
    }
    benchmark::DoNotOptimize(summary.points.data());
  }
  if (!summary.ok) state.SkipWithError(summary.message.c_str());
  SetCounters(state, n, summary.points.size());
}

TauGridOptions Octave() { return TauGridOptions{}; }
TauGridOptions Dense(int per_decade) {
  TauGridOptions grid;
  grid.kind = TauGridKind::kLogDense;
  grid.points_per_decade = per_decade;
  return grid;
}

void BM_OavarOctaveWarm(benchmark::State& state) {
  RunCurve(state, Statistic::kAllanOverlapping, Octave(), true);
}
void BM_OavarOctaveCold(benchmark::State& state) {
  RunCurve(state, Statistic::kAllanOverlapping, Octave(), false);
}
void BM_OavarDense10Warm(benchmark::State& state) {
  RunCurve(state, Statistic::kAllanOverlapping, Dense(10), true);
}
void BM_OhvarOctaveWarm(benchmark::State& state) {
  RunCurve(state, Statistic::kHadamardOverlapping, Octave(), true);
}
void BM_AvarOctaveWarm(benchmark::State& state) {
  RunCurve(state, Statistic::kAllanNonOverlapping, Octave(), true);
}
void BM_MvarOctaveWarm(benchmark::State& state) {
  RunCurve(state, Statistic::kModifiedAllan, Octave(), true);
}
void BM_TotvarOctaveWarm(benchmark::State& state) {
  RunCurve(state, Statistic::kTotal, Octave(), true);
}

// The older entry point used by `simulate` and the Monte Carlo test helpers.
void BM_AllanVarianceOctave(benchmark::State& state) {
  const std::int64_t n = state.range(0);
  const std::vector<double>& y = Record(n);
  const std::vector<std::int64_t> ms = OctaveAveragingFactors(n / 2);
  for (auto _ : state) {
    auto values = AllanVariance(y, ms, AvarEstimatorKind::kOverlapping);
    benchmark::DoNotOptimize(values.data());
  }
  SetCounters(state, n, ms.size());
}

constexpr std::int64_t k1e7 = 10'000'000;
constexpr std::int64_t k1e8 = 100'000'000;

BENCHMARK(BM_OavarOctaveWarm)->Arg(k1e7)->Arg(k1e8)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OavarOctaveCold)->Arg(k1e7)->Arg(k1e8)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OavarDense10Warm)->Arg(k1e7)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OhvarOctaveWarm)->Arg(k1e7)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AvarOctaveWarm)->Arg(k1e7)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MvarOctaveWarm)->Arg(k1e7)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TotvarOctaveWarm)->Arg(k1e7)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AllanVarianceOctave)->Arg(k1e7)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace allanlab::estimators

BENCHMARK_MAIN();
