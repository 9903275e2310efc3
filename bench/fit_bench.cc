// Coefficient fits on a 60-tau overlapping Allan curve (N = 2^20 samples at 100 Hz, N+B+K model,
// 5 terms asked). Target: a GLS fit of 5 terms on a 60-tau curve with the exact
// covariance <= 50 ms. Run: build/bench/fit_bench
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "estimators/allan_variance.h"
#include "estimators/fit/avar_covariance.h"
#include "estimators/fit/fit_avar_model.h"
#include "sim/sensor_model.h"

namespace allanlab::estimators {
namespace {

AvarCurve MakeCurve() {
  const std::int64_t n = std::int64_t{1} << 20;
  sim::SensorModel model;
  model.sample_clock = SampleClock::FromRateHz(100.0);
  model.terms = {TermFor(Coefficient::kN, FromDatasheetUnit(Coefficient::kN, 0.115)),
                 TermFor(Coefficient::kB, FromDatasheetUnit(Coefficient::kB, 6.0)),
                 TermFor(Coefficient::kK, FromDatasheetUnit(Coefficient::kK, 41.0))};
  AvarCurve c;
  c.sample_clock = SampleClock::FromPeriodS(0.01);
  c.num_samples = n;
  const double step = std::pow(static_cast<double>(n / 8), 1.0 / 59.0);  // 60 log-spaced taus
  for (double x = 1; c.m.size() < 60; x *= step) {
    const auto m = std::max<std::int64_t>(static_cast<std::int64_t>(std::llround(x)),
                                          c.m.empty() ? 1 : c.m.back() + 1);
    c.m.push_back(m);
  }
  for (std::int64_t m : c.m) c.tau_s.push_back(m * c.sample_clock.period_s());
  c.avar = AllanVariance(model.Generate(1, 0, n), c.m, sim::AvarEstimatorKind::kOverlapping);
  return c;
}

void BM_Fit(benchmark::State& state, FitMethod method, bool select) {
  const AvarCurve curve = MakeCurve();
  FitOptions options;
  options.method = method;
  options.select_terms = select;
  for (auto _ : state) {
    FitSummary s;
    benchmark::DoNotOptimize(FitAvarModel(options, curve, &s));
  }
}
BENCHMARK_CAPTURE(BM_Fit, wls_5_terms, FitMethod::kWls, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Fit, gls_5_terms, FitMethod::kGls, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Fit, gls_5_terms_with_selection, FitMethod::kGls, true)
    ->Unit(benchmark::kMillisecond);

void BM_CovarianceModel(benchmark::State& state) {
  const AvarCurve curve = MakeCurve();
  const std::vector<Coefficient> terms(std::begin(kAllCoefficients), std::end(kAllCoefficients));
  for (auto _ : state) {
    AvarCovarianceModel model(curve, terms);
    benchmark::DoNotOptimize(&model);
  }
}
BENCHMARK(BM_CovarianceModel)->Unit(benchmark::kMillisecond);

// The covariance model of `allanlab fit`'s default curve on a 1e7-sample record at 200 Hz
// (dense:10 taus up to N/8, as the end-to-end figure in results/benchmarks/fit.md), with and
// without flicker (B needs the record-length variogram table).
void BM_CovarianceModel1e7(benchmark::State& state) {
  AvarCurve c;
  c.sample_clock = SampleClock::FromPeriodS(0.005);
  c.num_samples = 10000000;
  for (double x = 1; x <= c.num_samples / 8; x *= std::pow(10.0, 0.1)) {
    const auto m = static_cast<std::int64_t>(std::llround(x));
    if (c.m.empty() || m > c.m.back()) c.m.push_back(m);
  }
  for (std::int64_t m : c.m) {
    c.tau_s.push_back(m * c.sample_clock.period_s());
    c.avar.push_back(1.0);
  }
  std::vector<Coefficient> terms(std::begin(kAllCoefficients), std::end(kAllCoefficients));
  if (state.range(0) == 0) terms.erase(terms.begin() + static_cast<int>(Coefficient::kB));
  for (auto _ : state) {
    AvarCovarianceModel model(c, terms);
    benchmark::DoNotOptimize(&model);
  }
  state.counters["taus"] = static_cast<double>(c.size());
}
BENCHMARK(BM_CovarianceModel1e7)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace allanlab::estimators

BENCHMARK_MAIN();
