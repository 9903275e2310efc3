#pragma once
// `allanlab simulate`: one rate record from a sensor model (a shipped preset or a YAML spec),
// written as CSV or raw float64 with provenance, optionally with its Allan diagram (PNG) and the
// numbers behind it (CSV): overlapping ADEV of the record at octave averaging factors m <= N/8,
// the exact expected value for this record length (SensorModel::ExpectedAvar) and the IEEE 952
// asymptote.
//
// The work is app/reports/simulated_record.h's. Exit codes (app/failure.h): 2 for a wrong command line or value (unknown preset, both or
// neither of --preset/--sensor, rate or duration not finite and > 0, fewer than 16 samples, unknown
// units or format, a --rate that puts the band-limit above the internal Nyquist frequency); 1 when
// a spec file cannot be loaded or is invalid, gnuplot is missing or fails, or an output cannot be
// written. Outputs are written through AtomicFile and committed together at the end, so a failed
// run leaves every existing file as it was.
#include <string>

#include <CLI/CLI.hpp>

#include "app/commands/subcommand.h"
#include "app/reports/simulated_record.h"

namespace allanlab::app {

Subcommand AddSimulateCommand(CLI::App* parent);

int RunSimulate(const SimulateOptions& options, const std::string& command_line);

}  // namespace allanlab::app
