#pragma once
// A declarative Monte Carlo sweep, written by people in YAML (an options struct with documented defaults, docs/architecture.md):
//
//   name: avar_error_bars             # names the output files
//   driver: avar_error_bars           # which TrialDriver runs a trial (experiments/drivers.h)
//   seed: 20261122
//   trials: 400                       # per sweep point
//   sensor:                           # exactly one of preset / model
//     preset: mg25_mems               #   a shipped preset (sim/sensor_spec.h), or
//     model: {sample_rate: 100 Hz, terms: [{type: arw, N: 0.1 deg/sqrt(h)}]}   # an inline spec
//   record: {duration: 1 h}           # or {samples: 1000000}; sample_rate from the sensor unless
//                                     #   record.sample_rate is given
//   estimators: [overlapping, nonoverlapping, modified, hadamard, total]   # statistic ids
//   taus: octave                      # octave | decade | dense:K | all | [0.01, 1, 10 s]
//                                     #   (a list of taus: seconds, or quantities with a unit)
//   fit: {methods: [slope, wls, log_wls, gls], terms: [Q, N, B, K, R]}   # optional; also
//        tau_range: [2.56 s, 80 s]   # the fits see only these taus, the same at every point
//   confidence: [0.683, 0.95]
//   sweep:                            # any parameter of the sensor or the record; values carry
//     mode: product                   #   units exactly as the sensor YAML does; product | zip
//     parameters:                     #   (quote paths with [ ] inside a flow mapping)
//       - {path: "sensor.terms[1].N", values: [0.01 deg/sqrt(h), 0.1 deg/sqrt(h)]}
//       - {path: record.duration, log_range: {from: 10 min, to: 24 h, points: 5}}
//       - {path: sensor.band_limit.cutoff, range: {from: 50 Hz, to: 200 Hz, step: 50 Hz}}
//
// A swept value is written as text into the sensor's YAML (sensor.<key path>, the preset's text
// when a preset is used) or into the record mapping (record.duration | samples | sample_rate),
// and every point's model is re-parsed by sim/, so any parameter can be swept and its units are
// checked there. record.sample_rate replaces the sensor's sample_rate. A range or log_range whose
// ends carry different units (10 min .. 24 h) is generated in the unit of `from`. Product mode:
// the first parameter varies slowest. Zip mode: all parameters need the same number of values.
//
// Unknown keys and impossible values are rejected before any work, with the key's path in the
// message (e.g. "sweep.parameters[1].log_range.points: must be >= 2").
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "estimators/statistic.h"
#include "sim/avar_theory.h"
#include "sim/sensor_model.h"

namespace allanlab::experiments {

// One swept parameter's value at a sweep point, as text with its unit (for tables) and the
// YAML path it was written to.
struct SweepCoordinate {
  std::string path;        // e.g. "sensor.terms[1].N"
  std::string value_text;  // e.g. "0.1 deg/sqrt(h)"
  double value = 0.0;      // the number in value_text's unit (for plots); NaN for a word
                           // (sensor values such as band_limit.type: first_order)
};

// One point of the sweep, fully resolved: the sensor model and record the trials simulate.
struct SweepPoint {
  int index = 0;                           // 0-based, in the spec's expansion order
  std::vector<SweepCoordinate> coordinates;  // empty when nothing is swept
  sim::SensorModel model;                  // its sample_clock is the record's
  std::int64_t num_samples = 0;
};

enum class SweepMode { kProduct, kZip };

struct SweepSpec {
  std::string name;
  std::string driver;
  std::uint64_t seed = 0;
  std::int64_t trials = 0;
  // Refined from sim::AvarEstimatorKind (which only knows the two Allan variances) so the
  // modified, Hadamard and total statistics the comment above lists can be asked for.
  std::vector<allanlab::estimators::Statistic> estimators;  // default {kAllanOverlapping}
  std::string taus = "octave";  // tau-grid spec as `allanlab avar --taus` (list: seconds, commas)
  std::vector<std::string> fit_methods;            // "slope", "wls", "log_wls", "gls", "default"
  std::vector<std::string> fit_terms;              // "Q", "N", ...
  // fit.tau_range: the fits use only taus in [fit_tau_min_s, fit_tau_max_s] (both 0 when the spec
  // gives none: then the driver's own rule decides, coefficient_trial.h).
  double fit_tau_min_s = 0.0;
  double fit_tau_max_s = 0.0;
  std::vector<double> confidence_levels = {0.683, 0.95};
  std::vector<SweepPoint> points;  // expanded and validated
  std::string canonical_text;      // normalised spec text: its hash names the checkpoint store
  std::uint64_t Hash() const;      // FNV-1a 64 of canonical_text
};

// Parses and expands a sweep spec; returns false with *why naming the key path on any error.
// `origin` names the source in messages (a file path).
bool LoadSweepSpecYaml(std::string_view yaml_text, std::string_view origin, SweepSpec* spec,
                       std::string* why);
bool LoadSweepSpecFile(const std::string& path, SweepSpec* spec, std::string* why);

}  // namespace allanlab::experiments
