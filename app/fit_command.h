#pragma once
// `allanlab fit FILE`: IEEE 952 coefficients (Q, N, B, K, R) of a recorded gyro with standard
// uncertainties, from its overlapping Allan curve (estimators/fit/fit_avar_model.h), with the
// slope-method reading beside each and the bandwidth from the short-tau inflection.
// Input options are those of `avar` (app/avar_command.h); default tau grid dense:10. Or, instead of
// FILE, a published curve: --curve CSV --record-length S --rate HZ (app/curve_options.h).
// One call of estimators::FitModel (estimators/fit/fit_model.h) does the fit.
// Outputs: a table on stdout; --json (method, coefficients with value, sigma, unit and
// profile-likelihood intervals, or an upper limit for a term the data do not determine;
// bandwidth_hz; fit chi2/dof/converged/poor_fit and the extended models tried on a poor fit;
// provenance); --kalibr (gyroscope noise density and random walk for Kalibr/VINS/OpenVINS; upper
// bounds under a warning on a poor fit); --plot (data with intervals, fitted total and each term).
// --strict: exit 1 on a poor fit (chi2 above its 99.9 % quantile) after writing the outputs. A short-tau band-limit is detected and fitted by default (--band-limit auto), the
// fitted cutoff reported beside the inflection reading; --min-tau/--max-tau restrict the taus.
// Units: Q urad, N deg/sqrt(h), B deg/h, K deg/h/sqrt(h), R deg/h^2 (an accelerometer column's:
// app/sensor_coefficients.h). Several columns (--columns, --imu): the record read once, a fit and
// a table per column, one JSON (columns[]), one Kalibr YAML for the IMU, one plot with every axis.
// --uncertainty bootstrap replaces the covariance sigmas by a parametric bootstrap
// (estimators/fit/parametric_bootstrap.h); table and JSON say which one was used.
// Exit codes as app/subcommand.h: 2 usage, 1 unreadable file, curve or fit failure.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>

#include "app/avar_command.h"
#include "app/curve_options.h"
#include "app/subcommand.h"

namespace allanlab::app {

struct FitCommandOptions {
  AvarCommandOptions curve;  // record and curve (estimator fixed to overlapping)
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

Subcommand AddFitCommand(CLI::App* parent);
int RunFit(const FitCommandOptions& options, const std::string& command_line);

}  // namespace allanlab::app
