#pragma once
// `allanlab diagnose FILE`: where a recording departs from its fitted IEEE 952 model, which
// unmodelled effect explains the gap and how far it shrinks (experiments/diagnosis/diagnose.h,
// docs/theory.md §6). Input options are those of `avar` (app/commands/avar_command.h).
//   (no baseline option) the baseline is what `allanlab fit` reports by default: Q,N,B,K,R plus
//                       a band-limit when the curve shows one (its cutoff then held)
//   --sensor SPEC.yaml | --preset NAME  the user's simulation model as the baseline: its
//                       coefficients, band-limit, quantizers and terms held as given
//   --float LIST        with --sensor/--preset: these IEEE coefficients (Q,N,B,K,R) refitted
//   --model LIST        a free IEEE baseline: only these terms, fitted (no band-limit)
//   --trials N --seed S simulated records per Monte Carlo envelope (default 30; 0: OAVAR only)
//   --false-alarm A     chance that a record of the model itself is flagged (default 0.05)
//   --jobs N            threads (default: every core; same output for any N)
//   --quiet             no progress line on stderr (there is none when stderr is not a terminal)
//   --progress          progress lines on stderr also when it is not a terminal
//   --json OUT          stable keys (add, never rename): gap{significant, threshold_z, regions[{view,
//                       tau_min_s, tau_max_s, max_abs_z}], views}, verdict{effect, params,
//                       also_consistent, separating_views}, candidates[{effect, params,
//                       gap_before, gap_after, heldout_gap_before, heldout_gap_after, score}],
//                       baseline{coefficients}, provenance. PSD regions also carry
//                       frequency_min_hz/frequency_max_hz, with tau = 1/(2 f).
//   --report OUT.md     the same for people, the plain-words summary first (diagnose_summary.h)
//   --plot OUT.png      ADEV: record, baseline, verdict model; a panel per other departing view
//   --html OUT.html     one self-contained page: the summary, the detail and the plot inline
//   --validate-on FILE2 a second recording of the same sensor: the verdict's model (linear terms
//                       refitted on FILE, effect included) scored on FILE2's OAVAR
// Several columns (--columns, --imu, or one accelerometer axis by --column): the record read once,
// a diagnosis per column, each in its sensor's units (app/reports/diagnose_units.h: a gyro's in deg/h, an
// accelerometer's in mg and m/s), one JSON (columns[]), report and plot (a panel per column).
// Curve mode (no record): --curve CSV --record-length S --rate HZ [--curve-column adev_x]
// [--curve-units deg/h]: an Allan-deviation table (tau_s, deviation columns) as published by
// other tools; OAVAR view only.
// Exit codes: 2 usage, 1 unreadable file or a record the diagnosis cannot use (too short,
// constant, non-finite values without --drop-nonfinite), 0 otherwise (whatever the verdict).
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "app/input/record_curve.h"
#include "app/input/curve_options.h"
#include "app/reports/provenance.h"
#include "app/reports/diagnose_units.h"
#include "app/commands/subcommand.h"
#include "experiments/diagnosis/diagnose.h"

namespace allanlab::app {

struct DiagnoseCommandOptions {
  RecordCurveOptions record;  // FILE and the input options of `avar`
  std::optional<std::string> model;  // unset: the fit's default baseline
  std::string sensor_path, preset, float_terms;
  int trials = 30;
  std::uint64_t seed = 1;
  double false_alarm = 0.05;
  int jobs = 0;        // threads (0: every core); the result is the same for any count
  bool quiet = false;  // no progress line on stderr
  bool progress = false;  // progress on stderr also when it is not a terminal
  std::string json_path, report_path, plot_path, html_path, validate_path;
  CurveCommandOptions curve;  // --curve mode (app/input/curve_options.h)
};

// Shared with the Python module (python/), which diagnoses a record in memory: the diagnosis
// options the command line asks for (baseline, trials, seed, false alarm; a failure is the error
// `diagnose` reports) ...
std::optional<CommandFailure> MakeDiagnoseOptions(const DiagnoseCommandOptions& o,
                                                  experiments::DiagnoseOptions* d);
// ... and the JSON `diagnose --json` writes for one column (validation: null, or the scores on a
// second record; units: the column's sensor and the unit it was read in, app/reports/diagnose_units.h).
nlohmann::ordered_json DiagnosisJson(const experiments::DiagnosisSummary& s, const Provenance& p,
                                     const nlohmann::ordered_json& validation, const DiagnoseUnits& units = {});

Subcommand AddDiagnoseCommand(CLI::App* parent);
int RunDiagnose(const DiagnoseCommandOptions& options, const std::string& command_line);

}  // namespace allanlab::app
