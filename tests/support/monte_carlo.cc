#include "tests/support/monte_carlo.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "estimators/allan_variance.h"
#include "estimators/exact_avar_variance.h"

namespace allanlab::testing_support {

AvarSample SimulateAvar(const sim::SensorModel& model, std::uint64_t seed, int trials,
                        std::int64_t n, std::span<const std::int64_t> ms,
                        sim::AvarEstimatorKind kind, const sim::GenerateOptions& options) {
  AvarSample s;
  s.trials = trials;
  s.mean.assign(ms.size(), 0.0);
  s.variance.assign(ms.size(), 0.0);
  std::vector<std::vector<double>> values(static_cast<std::size_t>(trials));
#pragma omp parallel for schedule(dynamic)
  for (int t = 0; t < trials; ++t) {
    const std::vector<double> y = model.Generate(seed, static_cast<std::uint64_t>(t), n, options);
    values[t] = estimators::AllanVariance(y, ms, kind);
  }
  for (std::size_t k = 0; k < ms.size(); ++k) {
    long double sum = 0.0L, sum2 = 0.0L;
    for (const auto& v : values) sum += v[k];
    const long double mean = sum / trials;
    for (const auto& v : values) sum2 += (v[k] - mean) * (v[k] - mean);
    s.mean[k] = static_cast<double>(mean);
    s.variance[k] = trials > 1 ? static_cast<double>(sum2 / (trials - 1)) : 0.0;
  }
  return s;
}

std::vector<double> ExactAvarStdDev(const sim::SensorModel& model, std::int64_t n,
                                    std::span<const std::int64_t> ms, sim::AvarEstimatorKind kind) {
  std::int64_t max_m = 1;
  for (std::int64_t m : ms) max_m = std::max(max_m, m);
  const std::vector<double> r = model.GaussianAutocovariance(n + 2 * max_m);
  std::vector<double> sd;
  for (std::int64_t m : ms) {
    sd.push_back(std::sqrt(estimators::ExactAvarMoments(r, m, {n, kind}).variance));
  }
  return sd;
}

::testing::AssertionResult MeanWithinTolerance(const AvarSample& sample,
                                               std::span<const double> expected,
                                               std::span<const double> sd_single,
                                               std::span<const std::int64_t> ms, double z) {
  std::ostringstream os;
  bool ok = true;
  os.precision(7);
  for (std::size_t k = 0; k < ms.size(); ++k) {
    const double tol = z * sd_single[k] / std::sqrt(static_cast<double>(sample.trials));
    const double diff = sample.mean[k] - expected[k];
    const bool pass = std::abs(diff) <= tol;
    ok = ok && pass;
    os << (pass ? "  " : "X ") << "m=" << ms[k] << " expected=" << expected[k]
       << " actual=" << sample.mean[k] << " tol=" << tol
       << " z=" << (tol > 0 ? diff / tol * z : 0.0) << "\n";
  }
  return ok ? ::testing::AssertionSuccess() << os.str()
            : ::testing::AssertionFailure() << os.str();
}

std::vector<std::int64_t> OctaveFactorsUpTo(std::int64_t max_m) {
  std::vector<std::int64_t> ms;
  for (std::int64_t m = 1; m <= max_m; m *= 2) ms.push_back(m);
  return ms;
}

sim::SensorModel SingleTermModel(const sim::NoiseTerm& term, double sample_rate_hz) {
  sim::SensorModel model;
  model.name = "single_term";
  model.sample_clock = SampleClock::FromRateHz(sample_rate_hz);
  model.terms = {term};
  return model;
}

QuantizerTheoryCheck CheckQuantizerTheory(const sim::SensorModel& model, const sim::SensorModel& unquantized,
                                          std::uint64_t seed, const std::function<double(std::int64_t m)>& white_avar) {
  constexpr std::int64_t kN = 1 << 14;
  constexpr int kTrials = 200;
  const std::vector<std::int64_t> ms = OctaveFactorsUpTo(kN / 8);
  const auto kind = sim::AvarEstimatorKind::kOverlapping;
  const AvarSample sample = SimulateAvar(model, seed, kTrials, kN, ms, kind);
  std::vector<double> sd;
  for (double v : sample.variance) sd.push_back(std::sqrt(v));
  QuantizerTheoryCheck check;
  check.exact = MeanWithinTolerance(sample, model.ExpectedAvar(ms, {kN, kind}), sd, ms);
  const auto signal = unquantized.ExpectedAvar(ms, {kN, kind});
  for (std::size_t i = 0; i < ms.size(); ++i) {
    const double white = signal[i] + white_avar(ms[i]);
    check.white_worst_z = std::max(check.white_worst_z, std::abs(sample.mean[i] - white) / (sd[i] / std::sqrt(kTrials)));
  }
  return check;
}

}  // namespace allanlab::testing_support
