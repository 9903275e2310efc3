#include "app/commands/simulate_command.h"

#include <charconv>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

namespace allanlab::app {
namespace {

constexpr const char* kCommand = "simulate";

// CLI11 reads "-1" into a uint64 as 2^64-1 and clamps overflow; a seed must be exactly what the
// user typed, so seeds are parsed here: decimal digits only, in range.
std::function<void(const std::string&)> DecimalUint64(const std::string& option,
                                                      std::uint64_t* value) {
  return [option, value](const std::string& text) {
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, *value);
    if (text.empty() || ec != std::errc() || ptr != end) {
      throw CLI::ValidationError(option,
                                 "expected an unsigned 64-bit decimal integer, got '" + text + "'");
    }
  };
}

}  // namespace

Subcommand AddSimulateCommand(CLI::App* parent) {
  auto options = std::make_shared<SimulateOptions>();
  CLI::App* cmd = parent->add_subcommand(
      kCommand,
      "Generate one gyro rate record from a sensor model and write it with provenance; "
      "optionally draw its Allan diagram against the exact theory.");
  const std::string presets = PresetList();
  cmd->add_option("--preset", options->preset,
                  "shipped sensor model: " + (presets.empty() ? "(none)" : presets))
      ->type_name("NAME");
  cmd->add_option("--sensor", options->sensor_path,
                  "sensor model YAML file, units on every value (format: sim/sensor_spec.h)")
      ->type_name("SPEC.yaml");
  cmd->add_option("--rate", options->rate_hz,
                  "output sample rate in Hz (default: the spec's sample_rate)")
      ->type_name("HZ");
  cmd->add_option("--duration", options->duration_s,
                  "record length in seconds; N = round(duration * rate) samples, at least 16")
      ->type_name("S")
      ->required();
  cmd->add_option_function<std::string>(
         "--seed", DecimalUint64("--seed", &options->seed),
         "random seed, an unsigned 64-bit decimal integer; same seed, trial and model => "
         "bit-identical record")
      ->type_name("N")
      ->required();
  cmd->add_option_function<std::string>(
         "--trial", DecimalUint64("--trial", &options->trial),
         "trial index (default 0): independent records under one seed")
      ->type_name("K");
  cmd->add_option("-o,--output", options->output_path,
                  "record file. csv: '#' provenance lines, then 'time_s,rate_<unit>' and one row "
                  "per sample (time in s); f64: raw little-endian float64 rates plus OUT.json "
                  "with the provenance")
      ->type_name("OUT")
      ->required();
  cmd->add_option("--format", options->format, "record format: csv or f64 (default: f64 for an output named *.f64, else csv)")
      ->type_name("csv|f64");
  cmd->add_option("--units", options->units,
                  "rate unit of the record: deg/s (default), deg/h or rad/s")
      ->type_name("deg/s|deg/h|rad/s");
  cmd->add_option(
         "--plot", options->plot_path,
         "also draw the Allan diagram (PNG, needs gnuplot): overlapping ADEV of the record "
         "in deg/h vs tau in s at octave m <= N/8, exact theory, IEEE 952 asymptote, "
         "slope guides")
      ->type_name("OUT.png");
  cmd->add_option("--avar-table", options->avar_table_path,
                  "also write the diagram's numbers as CSV: m, tau_s [s], oavar_sim, oavar_exact, "
                  "oavar_ieee [(rad/s)^2], adev_sim_deg_per_h, adev_exact_deg_per_h [deg/h]")
      ->type_name("OUT.csv");
  cmd->footer(
      "Outputs are written to a temporary file and renamed into place only when the whole run "
      "succeeds.\nExit status: 0 ok, 1 runtime error (spec file, I/O, gnuplot), 2 usage error.");
  return {cmd, [options](const std::string& command_line) {
            return RunSimulate(*options, command_line);
          }};
}

int RunSimulate(const SimulateOptions& options, const std::string& command_line) {
  return RunCommand(kCommand, "", [&] { return WriteSimulatedRecord(options, command_line); });
}

}  // namespace allanlab::app
