#pragma once
// `allanlab fit FILE`: IEEE 952 coefficients (Q, N, B, K, R) of a recorded gyro with standard
// uncertainties, from its overlapping Allan curve (estimators/fit/fit_avar_model.h), with the
// slope-method reading beside each and the bandwidth from the short-tau inflection.
// Input options are those of `avar` (app/commands/avar_command.h); default tau grid dense:10. Or, instead of
// FILE, a published curve: --curve CSV --record-length S --rate HZ (app/input/curve_options.h).
// One call of estimators::FitModel (estimators/fit/fit_model.h) does the fit.
// Outputs: a table on stdout; --json (method, coefficients with value, sigma, unit and
// profile-likelihood intervals, or an upper limit for a term the data do not determine;
// bandwidth_hz; fit chi2/dof/converged/poor_fit and the extended models tried on a poor fit;
// provenance); --kalibr (gyroscope noise density and random walk for Kalibr/VINS/OpenVINS; upper
// bounds under a warning on a poor fit); --plot (data with intervals, fitted total and each term).
// --strict: exit 1 on a poor fit (chi2 above its 99.9 % quantile) after writing the outputs. A short-tau band-limit is detected and fitted by default (--band-limit auto), the
// fitted cutoff reported beside the inflection reading; --min-tau/--max-tau restrict the taus.
// Units: Q urad, N deg/sqrt(h), B deg/h, K deg/h/sqrt(h), R deg/h^2 (an accelerometer column's:
// app/reports/sensor_coefficients.h). Several columns (--columns, --imu): the record read once, a fit and
// a table per column, one JSON (columns[]), one Kalibr YAML for the IMU, one plot with every axis.
// --uncertainty bootstrap replaces the covariance sigmas by a parametric bootstrap
// (estimators/fit/parametric_bootstrap.h); table and JSON say which one was used.
// Exit codes as app/commands/subcommand.h: 2 usage, 1 unreadable file, curve or fit failure.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "app/input/record_curve.h"
#include "app/reports/avar_report.h"
#include "app/input/imu_columns.h"
#include "app/reports/provenance.h"
#include "app/input/curve_options.h"
#include "app/commands/subcommand.h"
#include "estimators/fit/bandwidth_estimate.h"
#include "estimators/fit/fit_model.h"
#include "sim/sensor_model.h"

namespace allanlab::app {

// The tau grid `fit` computes the curve on unless --taus says otherwise.
inline constexpr const char* kFitTaus = "dense:10";

struct FitCommandOptions {
  RecordCurveOptions curve;  // record and curve (estimator fixed to overlapping)
  CurveCommandOptions published;  // --curve: a published curve instead of a record
  std::string method = "gls";           // slope, wls, logwls, gls
  std::string terms = "Q,N,B,K,R";      // asked terms
  bool select_terms = true;
  bool strict = false;  // exit 1 on a poor fit
  std::string uncertainty = "covariance";  // covariance or bootstrap
  int bootstrap_trials = 100;              // replicates of the parametric bootstrap
  std::uint64_t seed = 1;                  // of the bootstrap's simulated records
  // Band-limit handling (estimators/fit/band_limited_fit.h): auto (detect and fit) or off, and
  // the chain assumed for BW/BW2 (averaged or point-sampled output, oversampling L).
  std::string band_limit = "auto";
  std::string bw_sampling = "average";
  int bw_oversampling = 8;
  // Manual tau range of the fit, s (0 / inf: the whole curve).
  double min_tau_s = 0.0;
  double max_tau_s = 0.0;  // 0: no upper limit
  std::string json_path, kalibr_path, plot_path;
};

// The steps of `fit`, shared with the Python module (python/), which fits a record in memory:
// the fit options the command line asks for (--method, --terms, --band-limit, --min-tau ...; a
// failure is the usage error `fit` reports), with the tau range's upper end in *max_tau_s (inf
// when open) ...
std::optional<CommandFailure> MakeModelFitOptions(const FitCommandOptions& o, estimators::ModelFitOptions* fit,
                                                  double* max_tau_s);
// ... the options of the curve that is fitted (overlapping AVAR on o.curve's taus) ...
RecordCurveOptions FitCurveOptions(const FitCommandOptions& o);
// ... one curve's fit (the record must support the asked terms, app/input/record_support.h; warnings
// about weakly supported terms printed on stderr) ...
struct FittedAxis {
  estimators::AvarCurve curve;  // the taus fitted
  estimators::ModelFitSummary fitted;
  std::optional<sim::SensorModel> fitted_model;  // with parametric terms
  estimators::BandwidthEstimate bandwidth;
};
std::optional<CommandFailure> FitAxis(const FitCommandOptions& o, const estimators::ModelFitOptions& fit,
                                      double max_tau_s, const AvarReport* report, FittedAxis* axis);
Provenance FitProvenance(const FitCommandOptions& o, const AvarReport& report, const estimators::FitSummary& summary,
                         const std::string& command_line);
// ... and the JSON `fit --json` writes for it.
nlohmann::ordered_json FitJson(const FitCommandOptions& o, const estimators::ModelFitSummary& m,
                               const estimators::BandwidthEstimate& bw, const Provenance& p,
                               ImuSensor sensor = ImuSensor::kGyro);

Subcommand AddFitCommand(CLI::App* parent);
int RunFit(const FitCommandOptions& options, const std::string& command_line);

}  // namespace allanlab::app
