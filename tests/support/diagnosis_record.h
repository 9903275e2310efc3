#pragma once
// The short-record diagnosis the effect tests share: a record of the model (fixed seed, 3.6e4
// samples: 6 min at 100 Hz, so each test takes seconds) diagnosed with 12 Monte Carlo trials, and
// a one-line account of the verdict and candidates for failure messages.
#include <gtest/gtest.h>

#include <cstdint>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "experiments/diagnosis/diagnose.h"
#include "experiments/diagnosis/independent_case.h"
#include "independent/generate.h"
#include "independent/recipe.h"
#include "sim/sensor_model.h"
#include "sim/units.h"

namespace allanlab::testing {

inline constexpr std::int64_t kDiagnosisTestSamples = 36000;

// The options the diagnosis tests share: 12 Monte Carlo trials; `terms` the baseline's IEEE terms
// (empty: DiagnoseOptions' default Q, N, B, K, R).
inline experiments::DiagnoseOptions TestDiagnoseOptions(std::vector<estimators::Coefficient> terms = {}) {
  experiments::DiagnoseOptions options;
  options.trials = 12;
  if (!terms.empty()) options.terms = std::move(terms);
  return options;
}

inline experiments::DiagnosisSummary DiagnoseShortRecord(const sim::SensorModel& model, std::uint64_t seed) {
  const std::vector<double> record = model.Generate(seed, 0, kDiagnosisTestSamples);
  experiments::DiagnosisSummary s;
  EXPECT_TRUE(experiments::DiagnoseRecord(TestDiagnoseOptions(), record, model.sample_clock, &s))
      << s.message;
  return s;
}

// The user's model `--model N,B,K` as the baseline.
inline experiments::DiagnoseOptions UserModelNBK() {
  return TestDiagnoseOptions({estimators::Coefficient::kN, estimators::Coefficient::kB,
                              estimators::Coefficient::kK});
}

// A MEMS gyro of the independent generator at 100 Hz: white rate noise N [deg/sqrt(h)], bias
// instability B [deg/h] as a flicker floor, rate random walk K [deg/h/sqrt(h)], no other term.
inline independent::Recipe IndependentMemsGyro(double n_deg_per_sqrt_h, double b_deg_per_h,
                                               double k_deg_per_h_per_sqrt_h) {
  independent::Recipe r;
  r.rate_hz = 100.0;
  r.noise.arw_rad_per_sqrt_s = units::DegPerSqrtHour(n_deg_per_sqrt_h);
  r.noise.flicker_floor_rad_per_s = independent::FlickerFloorFromB(units::DegPerHour(b_deg_per_h));
  r.noise.rrw_rad_per_s_per_sqrt_s = units::DegPerHourPerSqrtHour(k_deg_per_h_per_sqrt_h);
  return r;
}

// A record of the independent generator (independent/generate.h: written apart from sim/) of n
// samples for `seed`, diagnosed with `options`.
inline experiments::DiagnosisSummary DiagnoseIndependentRecord(const independent::Recipe& recipe,
                                                               std::int64_t n, std::uint64_t seed,
                                                               const experiments::DiagnoseOptions& options) {
  const std::vector<double> record = independent::Generate(recipe, n, seed, 0);
  experiments::DiagnosisSummary s;
  EXPECT_TRUE(experiments::DiagnoseRecord(options, record, SampleClock::FromRateHz(recipe.rate_hz), &s)) << s.message;
  return s;
}

// The draw the independent benchmark's tables were made with (`diagnosis-benchmark
// --independent-control-fraction 0.6`, resonances among the effects), whatever the seed.
inline experiments::IndependentDrawOptions CommittedBenchmarkDraw() {
  experiments::IndependentDrawOptions o;
  o.control_fraction = 0.6;
  o.with_resonance = true;
  return o;
}

// Record `index` of the independent diagnosis benchmark's draw with `seed` (the draw and the
// generator's stream as diagnosis-benchmark makes them), its case in *c; empty on a failed draw.
inline std::vector<double> IndependentBenchmarkRecord(const experiments::IndependentDrawOptions& draw,
                                                      std::uint64_t seed, int index,
                                                      experiments::IndependentCase* c) {
  std::string why;
  if (!experiments::DrawIndependentCase(draw, seed, index, c, &why)) {
    ADD_FAILURE() << why;
    return {};
  }
  return independent::Generate(c->recipe, c->num_samples, seed, static_cast<std::uint64_t>(index));
}

inline std::string DescribeVerdict(const experiments::DiagnosisSummary& s) {
  std::ostringstream out;
  out << s.verdict << " (also:";
  for (const auto& a : s.also_consistent) out << " " << a.effect;
  out << ") candidates:";
  for (const auto& c : s.candidates) {
    out << " " << c.id() << " score " << c.score << " full " << c.full_score << " max|z| "
        << c.after.All().max_abs_z << (c.closes_gap ? " closes" : "");
    for (const auto& [k, v] : c.effects[0].params) out << " " << k << "=" << v;
    out << ";";
  }
  return out.str();
}

}  // namespace allanlab::testing
