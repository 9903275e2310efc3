#pragma once
// Validation table 4, `record_length`: how the error of each coefficient shrinks with
// the record length T, per method.
//
// Method: the trials of coefficient_recovery (CoefficientTrialDriver) on a sweep of T; per
// sensor, method and coefficient, a weighted least-squares line through ln RMSE vs ln T (weights
// from the Monte Carlo standard error of each RMSE; the slope's error is scaled up by
// sqrt(chi2/dof) when the points scatter more than their errors), over the record lengths where
// the coefficient is identifiable (relative RMSE <= kIdentifiableRmse: the linear regime; above
// it the estimates pile up at the zero bound and the RMSE saturates near 1).
//
// Two designs, told apart by the spec:
//  * fit.tau_range given (the same fitted taus at every T): T changes only the number of
//    clusters at each fitted tau, the covariance of the curve scales as 1/T (docs/theory.md §3.2,
//    EDF ~ T/tau), so every identifiable coefficient of a consistent fit has relative error
//    ~ T^-1/2. Reference slope -1/2; "met" when the slope's 95 % interval lies inside
//    -1/2 +- kSlopeTolerance, "not met" when it lies outside (a method with a bias floor, the slope
//    method where terms overlap, docs/theory.md §4.5, flattens towards 0), else "undecided".
//  * no fit.tau_range: the fitted taus grow with T (the band-limit rule of coefficient_trial.h
//    raises the shortest, the record the longest), so the slope mixes the extra clusters with the
//    moved tau range; no reference slope is printed. Set beside the fixed-range table of the same
//    sensor, the difference is the tau range's effect.
#include <string>
#include <vector>

#include "estimators/fit/noise_coefficient.h"
#include "experiments/coefficient_trial.h"
#include "experiments/experiment.h"

namespace allanlab::experiments {

// Relative RMSE above which a coefficient counts as not identifiable at a record length.
inline constexpr double kIdentifiableRmse = 0.3;
// Half-width of the band around the reference slope -1/2 inside which a slope is "met".
inline constexpr double kSlopeTolerance = 0.1;

// Weighted least-squares line y = a + b x with standard errors sigma; returns false with fewer
// than 2 usable points. slope_se is scaled by sqrt(chi2/dof) when that exceeds 1 (dof >= 1).
struct LogLogSlope {
  int points = 0;
  double slope = 0.0;
  double slope_se = 0.0;
  double intercept = 0.0;
  double chi2 = 0.0;
  int dof = 0;
};
bool FitLine(const std::vector<double>& x, const std::vector<double>& y,
             const std::vector<double>& sigma, LogLogSlope* line);

class RecordLengthExperiment : public DriverExperiment<CoefficientTrialDriver> {
 public:
  using DriverExperiment::DriverExperiment;
  std::string Name() const override { return "record_length"; }
  std::string Question() const override;
  // <spec.name>.csv, .md and <spec.name>_<sensor>_<coefficient>.{png,svg} (relative RMSE vs T,
  // with the T^-1/2 reference through GLS when the tau range is fixed).
  bool WriteReport(const SweepSpec& spec, const RunSummary& run,
                   const std::vector<PointStats>& stats, const ReportContext& context,
                   std::string* why) const override;
};

}  // namespace allanlab::experiments
