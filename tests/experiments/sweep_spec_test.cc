#include "experiments/sweep_spec.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace allanlab::experiments {
namespace {

constexpr const char* kBase = R"(
name: t
driver: avar_bias
seed: 7
trials: 3
sensor: {model: {name: m, sample_rate: 100 Hz, terms: [{type: arw, N: 0.1 deg/sqrt(h)}, {type: rrw, K: 1 deg/h/sqrt(h)}], band_limit: {type: first_order, cutoff: 20 Hz}}}
record: {duration: 10 s}
)";

SweepSpec MustLoad(const std::string& text) {
  SweepSpec spec;
  std::string why;
  EXPECT_TRUE(LoadSweepSpecYaml(text, "spec.yaml", &spec, &why)) << why;
  return spec;
}

std::string Error(const std::string& text) {
  SweepSpec spec;
  std::string why;
  EXPECT_FALSE(LoadSweepSpecYaml(text, "spec.yaml", &spec, &why)) << text;
  return why;
}

TEST(SweepSpec, UnsweptSpecIsOnePointWithDefaults) {
  const SweepSpec spec = MustLoad(kBase);
  ASSERT_EQ(spec.points.size(), 1u);
  EXPECT_EQ(spec.points[0].num_samples, 1000);
  EXPECT_EQ(spec.points[0].model.sample_clock.rate_hz(), 100.0);
  EXPECT_TRUE(spec.points[0].coordinates.empty());
  ASSERT_EQ(spec.estimators.size(), 1u);
  EXPECT_EQ(spec.estimators[0], estimators::Statistic::kAllanOverlapping);
  EXPECT_EQ(spec.taus, "octave");
  EXPECT_EQ(spec.trials, 3);
  EXPECT_EQ(spec.seed, 7u);
}

TEST(SweepSpec, ProductSweepsSensorAndRecordFirstParameterSlowest) {
  const SweepSpec spec = MustLoad(std::string(kBase) + R"(
sweep:
  parameters:
    - {path: 'sensor.terms[0].N', values: [0.01 deg/sqrt(h), 0.1 deg/sqrt(h)]}
    - {path: sensor.band_limit.cutoff, range: {from: 10 Hz, to: 30 Hz, step: 10 Hz}}
)");
  ASSERT_EQ(spec.points.size(), 6u);
  EXPECT_EQ(spec.points[1].coordinates[0].value_text, "0.01 deg/sqrt(h)");
  EXPECT_EQ(spec.points[1].coordinates[1].value_text, "20 Hz");
  EXPECT_EQ(spec.points[3].coordinates[0].value_text, "0.1 deg/sqrt(h)");
  EXPECT_EQ(spec.points[3].coordinates[1].value_text, "10 Hz");
  EXPECT_DOUBLE_EQ(spec.points[5].model.band_limit.cutoff_hz, 30.0);
  // N = 0.01 deg/sqrt(h) in rad/sqrt(s): the value reached sim/ through the YAML.
  const double n_si = 0.01 * M_PI / 180.0 / 60.0;
  const auto* arw = std::get_if<sim::WhiteRateNoise>(&spec.points[0].model.terms[0]);
  ASSERT_NE(arw, nullptr);
  EXPECT_NEAR(arw->arw_rad_per_sqrt_s, n_si, 1e-15);
}

TEST(SweepSpec, LogRangeInTheUnitOfFromAndZip) {
  const SweepSpec spec = MustLoad(std::string(kBase) + R"(
sweep:
  mode: zip
  parameters:
    - {path: record.duration, log_range: {from: 1 min, to: 1 h, points: 3}}
    - {path: record.sample_rate, values: [10 Hz, 20 Hz, 50 Hz]}
)");
  ASSERT_EQ(spec.points.size(), 3u);
  EXPECT_EQ(spec.points[0].coordinates[0].value_text, "1 min");
  EXPECT_EQ(spec.points[2].coordinates[0].value_text, "60 min");
  EXPECT_EQ(spec.points[0].num_samples, 600);
  EXPECT_EQ(spec.points[2].num_samples, 3600 * 50);
  EXPECT_EQ(spec.points[2].model.sample_clock.rate_hz(), 50.0);
  EXPECT_NEAR(spec.points[1].coordinates[0].value, std::sqrt(60.0), 1e-12);
}

TEST(SweepSpec, PresetAndSamplesAndHashFollowTheContent) {
  const std::string preset = R"(
name: p
driver: avar_bias
seed: 1
trials: 2
sensor: {preset: mg25_mems}
record: {samples: 4096}
estimators: [overlapping, nonoverlapping, modified]
taus: [0.01, 100 ms]
fit: {methods: [gls, slope]}
confidence: [0.9]
)";
  const SweepSpec a = MustLoad(preset);
  EXPECT_EQ(a.points[0].num_samples, 4096);
  EXPECT_EQ(a.points[0].model.name, "mg25_mems");
  EXPECT_EQ(a.estimators.size(), 3u);
  EXPECT_EQ(a.fit_terms.size(), 5u);
  EXPECT_EQ(a.taus, "0.01,0.10000000000000001");
  EXPECT_EQ(a.Hash(), MustLoad(preset).Hash());
  std::string changed = preset;
  changed.replace(changed.find("seed: 1"), 7, "seed: 2");
  EXPECT_NE(a.Hash(), MustLoad(changed).Hash());
}

struct ErrorCase {
  std::string yaml;
  std::string expected;  // a substring of the message: the key path and the reason
};

TEST(SweepSpec, EveryErrorNamesItsKey) {
  const std::string b = kBase;
  auto replace = [&](std::string what, std::string with) {
    std::string text = b;
    text.replace(text.find(what), what.size(), with);
    return text;
  };
  const ErrorCase cases[] = {
      {b + "colour: red\n", "colour: unknown key"},
      {replace("trials: 3", "trials: 0"), "trials: must be >= 1"},
      {replace("trials: 3", "trials: many"), "trials: expected an integer"},
      {replace("seed: 7", "seed: -1"), "seed: expected a non-negative integer"},
      {replace("driver: avar_bias", "driver: nope"), "driver: unknown experiment \"nope\""},
      {replace("name: t\n", ""), "name: missing"},
      {replace("{duration: 10 s}", "{duration: 0.05 s}"), "record.duration: the record has 5 samples"},
      {replace("{duration: 10 s}", "{duration: 10}"), "record.duration:"},
      {replace("{duration: 10 s}", "{duration: 10 s, samples: 5}"), "record: exactly one of"},
      {replace("{duration: 10 s}", "{duration: 10 s, length: 5}"), "record.length: unknown key"},
      {replace("sensor: {model:", "sensor: {preset: nope, model:"), "sensor: exactly one"},
      {replace("record: {duration: 10 s}", "record: {duration: 10 s}\nestimators: [overlapping, bogus]"),
       "estimators[1]: unknown estimator \"bogus\""},
      {b + "taus: sometimes\n", "taus:"},
      {b + "taus: [1 Hz]\n", "taus[0]:"},
      {b + "fit: {methods: [wls, lsq]}\n", "fit.methods[1]: unknown fit method \"lsq\""},
      {b + "fit: {methods: [wls], terms: [N, X]}\n", "fit.terms[1]: unknown coefficient"},
      {b + "fit: {method: wls}\n", "fit.method: unknown key"},
      {b + "fit: {methods: [gls], tau_range: [1 s]}\n", "fit.tau_range: expected [shortest tau, longest tau]"},
      {b + "fit: {methods: [gls], tau_range: [1 s, 2 Hz]}\n", "fit.tau_range[1]:"},
      {b + "fit: {methods: [gls], tau_range: [0 s, 2 s]}\n", "fit.tau_range[0]: must be > 0"},
      {b + "fit: {methods: [gls], tau_range: [4 s, 2 s]}\n", "fit.tau_range: the longest tau must exceed"},
      {b + "confidence: [0.5, 1.5]\n", "confidence[1]: expected a level in (0, 1)"},
      {b + "sweep: {mode: cross, parameters: [{path: record.duration, values: [1 s]}]}\n",
       "sweep.mode: expected product or zip"},
      {b + "sweep: {parameters: [{path: 'sensor.terms[0].N', log_range: {from: 1 deg/sqrt(h), to: 2 deg/sqrt(h), points: 1}}]}\n",
       "sweep.parameters[0].log_range.points: must be >= 2"},
      {b + "sweep: {parameters: [{path: 'sensor.terms[0].N', range: {from: 1 deg/sqrt(h), to: 2 deg/sqrt(h), step: 0 deg/sqrt(h)}}]}\n",
       "sweep.parameters[0].range.step: must be > 0"},
      {b + "sweep: {parameters: [{path: 'sensor.terms[0].N', range: {from: 1 deg/sqrt(h), to: 2 Hz, step: 1 deg/sqrt(h)}}]}\n",
       "sweep.parameters[0].range.to: unit \"Hz\""},
      {b + "sweep: {parameters: [{path: 'sensor.terms[5].N', values: [1 deg/sqrt(h)]}]}\n",
       "sweep.parameters[0].path: \"terms[5]\" does not exist"},
      {b + "sweep: {parameters: [{path: record.length, values: [1 s]}]}\n",
       "sweep.parameters[0].path: \"record.length\" is neither"},
      {b + "sweep: {parameters: [{path: 'sensor.terms[0].N', values: [-1 deg/sqrt(h)]}]}\n",
       "point 0 (sensor.terms[0].N = -1 deg/sqrt(h))"},
      {b + "sweep: {parameters: [{path: 'sensor.terms[0].N', values: [1 Hz]}]}\n", "terms[0].N"},
      {b + "sweep: {parameters: [{path: record.duration, values: [1 s, 0.01 s]}]}\n",
       "point 1 (record.duration = 0.01 s): record.duration: the record has 1 samples"},
      {b + "sweep: {mode: zip, parameters: [{path: record.duration, values: [1 s, 2 s]}, {path: 'sensor.terms[0].N', values: [1 deg/sqrt(h)]}]}\n",
       "sweep.parameters[1]: zip mode needs equal lengths"},
      {b + "sweep: {parameters: [{path: record.duration, values: [1 s], range: {from: 1 s, to: 2 s, step: 1 s}}]}\n",
       "sweep.parameters[0]: exactly one of values, range or log_range"},
      {"name: [\n", "spec.yaml:"},
  };
  for (const ErrorCase& c : cases) {
    const std::string why = Error(c.yaml);
    EXPECT_NE(why.find(c.expected), std::string::npos) << "message: " << why << "\nexpected: " << c.expected;
    EXPECT_EQ(why.rfind("spec.yaml", 0), 0u) << why;
    EXPECT_EQ(why.find('\n'), std::string::npos) << why;
  }
}

TEST(SweepSpec, FitTauRangeIsReadInSecondsAndNamesTheCheckpoint) {
  const SweepSpec plain = MustLoad(std::string(kBase) + "fit: {methods: [gls]}\n");
  EXPECT_EQ(plain.fit_tau_max_s, 0.0);
  const SweepSpec fixed = MustLoad(std::string(kBase) + "fit: {methods: [gls], tau_range: [2.56 s, 1 min]}\n");
  EXPECT_DOUBLE_EQ(fixed.fit_tau_min_s, 2.56);
  EXPECT_DOUBLE_EQ(fixed.fit_tau_max_s, 60.0);
  EXPECT_NE(plain.Hash(), fixed.Hash());
}

TEST(SweepSpec, MissingFileIsAnError) {
  SweepSpec spec;
  std::string why;
  EXPECT_FALSE(LoadSweepSpecFile("/nonexistent/spec.yaml", &spec, &why));
  EXPECT_NE(why.find("/nonexistent/spec.yaml"), std::string::npos);
}

}  // namespace
}  // namespace allanlab::experiments
