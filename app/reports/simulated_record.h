#pragma once
// One rate record simulated from a sensor model (a shipped preset or a YAML spec) and written as
// CSV or raw float64 with provenance (`allanlab simulate`, and the blind diagnosis benchmark's
// recordings), optionally with its Allan diagram (PNG) and the numbers behind it (CSV):
// overlapping ADEV of the record at octave averaging factors m <= N/8, the exact expected value
// for this record length (SensorModel::ExpectedAvar) and the IEEE 952 asymptote.
//
// Failures (app/failure.h): usage for a wrong value (unknown preset, both or neither of
// preset/sensor, rate or duration not finite and > 0, fewer than 16 samples, unknown units or
// format, a rate that puts the band-limit above the internal Nyquist frequency); runtime when a
// spec file cannot be loaded or is invalid, gnuplot is missing or fails, or an output cannot be
// written. Outputs are written through AtomicFile and committed together at the end, so a failed
// run leaves every existing file as it was.
#include <cstdint>
#include <optional>
#include <string>

#include "app/failure.h"
#include "sim/sensor_model.h"

namespace allanlab::app {

// What to simulate and where to write it (the `simulate` command line as parsed); strings are
// checked by WriteSimulatedRecord, not by the parser, so that every error has the same one-line form.
struct SimulateOptions {
  std::string preset;             // shipped preset name; exclusive with sensor_path
  std::string sensor_path;        // YAML sensor spec (sim/sensor_spec.h)
  std::optional<double> rate_hz;  // output rate [Hz]; default: the spec's sample_rate
  double duration_s = 0.0;        // record length [s]; N = round(duration * rate) >= 16
  std::uint64_t seed = 0;         // with trial, selects the random streams (sim/seeding.h)
  std::uint64_t trial = 0;
  std::string output_path;      // the record
  // "csv" or "f64" (raw little-endian float64 + OUT.json); empty: from the output's name (.f64 is
  // f64, anything else csv). A stated format that contradicts a .csv or .f64 name is an error.
  std::string format;
  std::string units = "deg/s";  // "deg/s", "deg/h" or "rad/s"
  std::string plot_path;        // optional Allan diagram (PNG)
  std::string avar_table_path;  // optional Allan table (CSV)
};

// Smallest record the command accepts: N/8 >= 2 gives at least two octave points.
inline constexpr std::int64_t kMinSimulateSamples = 16;

// Registers `simulate` on `parent`.
// Shared with the Python module (python/), which simulates into memory: the sensor model the
// options name (a preset or a YAML spec, --rate applied) ...
std::optional<CommandFailure> LoadSimulateModel(const SimulateOptions& o, sim::SensorModel* model);
// ... and the record's sample count, round(duration * rate) >= kMinSimulateSamples.
std::optional<CommandFailure> SimulateSampleCount(const SimulateOptions& o, double sample_rate_hz,
                                                  std::int64_t* n);

// The shipped presets' names, comma separated (sim::PresetNames()).
std::string PresetList();

// Simulates o's record and writes it with the outputs o asks for; `command_line` goes into the
// provenance. Nothing is printed.
std::optional<CommandFailure> WriteSimulatedRecord(const SimulateOptions& o, const std::string& command_line);

}  // namespace allanlab::app
