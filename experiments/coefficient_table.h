#pragma once
// The per-(point, method, coefficient) summary both coefficient tables print, computed from the
// aggregated columns of CoefficientTrialDriver (coefficient_trial.h). All errors are relative to
// the true coefficient; each number carries its Monte Carlo standard error.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "common/sample_clock.h"
#include "estimators/fit/noise_coefficient.h"
#include "experiments/aggregate.h"
#include "experiments/runner.h"
#include "experiments/sweep_spec.h"

namespace allanlab::experiments {

struct CoefficientRow {
  int point = 0;
  std::string sensor;        // model name
  double duration_s = 0.0;   // record length T
  SampleClock sample_clock;
  std::int64_t samples = 0;
  std::string method;        // slope, wls, log_wls, gls
  estimators::Coefficient coefficient = estimators::Coefficient::kN;
  double truth_si = 0.0;
  std::int64_t n = 0;               // trials with an estimate
  double failure_rate = 0.0;        // trials without one
  double bias = 0.0, bias_se = 0.0;  // mean(estimate / truth - 1)
  double rmse = 0.0, rmse_se = 0.0;  // sqrt(mean((estimate / truth - 1)^2))
  double empirical_sd = 0.0;         // std of estimate / truth
  double mean_sigma = 0.0;           // mean reported sigma / truth (NaN for slope)
  // mean_sigma / empirical_sd (1 = honest error bars) and its standard error by the delta method:
  // the mean's own error and the sd's, se(sd) ~ se(mean squared error) / (2 sd), which takes the
  // errors' fourth moment from the trials (conservative when the bias is not small against the
  // sd); the correlation between a trial's reported sigma and its error is neglected.
  double sigma_ratio = 0.0, sigma_ratio_se = 0.0;
  std::vector<double> coverage;      // per confidence level (NaN for slope)
  std::vector<double> coverage_se;   // binomial, at the nominal level
  // Wilson score 95 % interval of each coverage (from its count of trials).
  std::vector<double> coverage_low, coverage_high;
  // Slope method's B against sqrt(B^2 + 2.617 N K) (NaN otherwise).
  double read_bias = 0.0, read_bias_se = 0.0;
};

std::vector<CoefficientRow> CoefficientRows(const SweepSpec& spec,
                                            const std::vector<PointStats>& stats);

// "10 min", "2 h", "24 h".
std::string DurationText(double seconds);
// A table cell: "%.*g" with `digits` significant digits, "" for NaN (not available).
std::string Cell(double value, int digits = 6);
// A CSV field, quoted when it holds a comma, quote or newline.
std::string CsvField(const std::string& text);

}  // namespace allanlab::experiments

namespace allanlab::experiments {

// The fixed choices of CoefficientTrialDriver, the sensors of the spec and the run's cost, as
// the `extra` provenance fields (fit taus per point, slope curve, term selection, wall time).
std::vector<std::pair<std::string, std::string>> CoefficientTrialChoices(const SweepSpec& spec,
                                                                         const RunSummary& run);

// A straight line on a log-log panel: y = anchor_y (x / anchor_x)^slope (x = T in s).
struct GuideLine {
  std::string sensor;
  estimators::Coefficient coefficient = estimators::Coefficient::kN;
  double slope = -0.5;
  double anchor_x = 1.0;
  double anchor_y = 1.0;
  std::string title;
};

// gnuplot body (for RenderGnuplotFigure): a log-log plot of coefficient c of `sensor`, relative
// RMSE (points with Monte Carlo error bars, solid) and |bias| (dashed) of every method vs T in
// hours, plus the guide lines of c.
std::string CoefficientPlotBody(const std::vector<CoefficientRow>& rows, const std::string& sensor,
                                estimators::Coefficient c, const std::string& title,
                                const std::vector<GuideLine>& guides);
// "<base>_<sensor>_<coefficient>" for each (sensor, coefficient) of the rows, rendered with
// CoefficientPlotBody; *files gets the Markdown image lines.
bool RenderCoefficientPlots(const std::vector<CoefficientRow>& rows, const std::string& base,
                            const std::string& title_prefix, const std::vector<GuideLine>& guides,
                            std::string* markdown_images, std::string* why);
// The report of a coefficient experiment: the plots of RenderCoefficientPlots, then <base>.csv
// and <base>.md (the Markdown with a Figures section appended), each written atomically.
bool WriteCoefficientReport(const std::vector<CoefficientRow>& rows, const std::string& base,
                            const std::string& title_prefix, const std::vector<GuideLine>& guides,
                            const std::string& csv, const std::string& markdown, std::string* why);

}  // namespace allanlab::experiments
