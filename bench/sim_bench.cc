// Generator throughput (ns per output sample, one core) for each noise term and for full
// band-limited presets. Run: build/bench/sim_bench --benchmark_counters_tabular=true
// Issue targets: white, random walk, Gauss-Markov <= 8 ns/sample; flicker <= 100 ns/sample;
// a full band-limited preset <= 200 ns/sample, at N = 2^22.
#include <benchmark/benchmark.h>

#include <string>
#include <variant>
#include <vector>

#include "sim/sensor_model.h"
#include "sim/sensor_spec.h"

namespace allanlab::sim {
namespace {

constexpr std::int64_t kSamples = std::int64_t{1} << 22;

// A whole sensor model, allocation of the record included (what `simulate` pays).
void RunModel(benchmark::State& state, const SensorModel& model) {
  std::uint64_t trial = 0;
  for (auto _ : state) {
    auto y = model.Generate(1, trial++, kSamples);
    benchmark::DoNotOptimize(y.data());
  }
  state.SetItemsProcessed(state.iterations() * kSamples);
  // Seconds per sample, printed with an SI prefix ("5.2n" = 5.2 ns per sample).
  state.counters["s_per_sample"] = benchmark::Counter(
      static_cast<double>(state.iterations() * kSamples),
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// A term's generator alone, adding into a reused buffer (as a Monte Carlo runner does).
void BM_Term(benchmark::State& state, NoiseTerm term) {
  std::vector<double> buffer(static_cast<std::size_t>(kSamples), 0.0);
  std::uint64_t trial = 0;
  for (auto _ : state) {
    Engine engine = MakeEngine(1, trial++, 0);
    std::visit([&](const auto& t) { t.AddTo(engine, 1.0 / 200.0, buffer); }, term);
    benchmark::DoNotOptimize(buffer.data());
  }
  state.SetItemsProcessed(state.iterations() * kSamples);
  state.counters["s_per_sample"] = benchmark::Counter(
      static_cast<double>(state.iterations() * kSamples),
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

BENCHMARK_CAPTURE(BM_Term, white, NoiseTerm{WhiteRateNoise{1e-3}})->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Term, quantization, NoiseTerm{QuantizationNoise{1e-6}})->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Term, random_walk, NoiseTerm{RandomWalkRate{1e-5}})->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Term, gauss_markov, NoiseTerm{GaussMarkov{1e-4, 10.0}})->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Term, flicker_kasdin, NoiseTerm{FlickerNoise{1e-5}})->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Term, flicker_gm_sum_8, NoiseTerm{FlickerGaussMarkovSum{1e-5, 0.1, 1e6, 1.0}})
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Term, telegraph, NoiseTerm{RandomTelegraph{1e-4, 10.0}})->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Term, harmonic, NoiseTerm{Harmonic{1e-4, 7.3, std::nullopt}})->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Term, outliers, NoiseTerm{Outliers{0.01, 1e-2}})->Unit(benchmark::kMillisecond);

void BM_Preset(benchmark::State& state, std::string name) {
  SensorModel model;
  std::string why;
  if (!LoadPreset(name, &model, &why)) {
    state.SkipWithError(why.c_str());
    return;
  }
  RunModel(state, model);
}
BENCHMARK_CAPTURE(BM_Preset, mg25_mems, std::string("mg25_mems"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Preset, tg100, std::string("tg100"))->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace allanlab::sim

BENCHMARK_MAIN();
