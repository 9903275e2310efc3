#pragma once
// Validation table 4, `record_length`: how the error of each coefficient shrinks with
// the record length T, per method, against the slope the theory predicts.
//
// Method: the trials of coefficient_recovery (CoefficientTrialDriver) on a sweep of T; per
// sensor, method and coefficient, a weighted least-squares line through ln RMSE vs ln T (weights
// from the Monte Carlo standard error of each RMSE; the slope's error is scaled up by
// sqrt(chi2/dof) when the points scatter more than their errors, e.g. across a crossover).
// Reference (theory slope, PredictedErrorSlope): a coefficient estimated from taus where its own
// term dominates has a relative error ~ sqrt(1/EDF) with EDF ~ T/tau at a fixed tau (docs/theory.md
// §2.2), i.e. T^-1/2; this holds for Q and N (short taus, EDF ~ T/tau_min), and for B and K once
// their region lies inside the record. A long-tau term that never dominates in the record (tau^mu
// under a dominant tau^nu at the longest taus) is seen only as a perturbation there: its squared
// coefficient has Fisher information ~ T^(2(mu - nu)), so its relative error goes as
// T^-(mu - nu): B under white noise T^-1, K under flicker T^-1, K under white T^-2.
// A method whose error has a bias floor (the slope method where terms overlap, docs/theory.md §4.5)
// flattens to slope 0. Pass criterion: the consistent fits' slopes match the theory within ~2
// standard errors.
#include <vector>

#include "estimators/fit/noise_coefficient.h"
#include "experiments/coefficient_trial.h"
#include "experiments/experiment.h"

namespace allanlab::experiments {

// Theory slope d ln(relative error) / d ln T for coefficient c of `truth` when the fit sees taus
// in [tau_min_s, tau_max_s] (asymptotic IEEE 952 shapes decide which term dominates where).
double PredictedErrorSlope(const TrueCoefficients& truth, estimators::Coefficient c,
                           double tau_min_s, double tau_max_s);

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

class RecordLengthExperiment : public Experiment {
 public:
  RecordLengthExperiment() = default;
  explicit RecordLengthExperiment(InjectedFault fault) : driver_(fault) {}
  std::string Name() const override { return "record_length"; }
  std::string Question() const override;
  const TrialDriver& Driver() const override { return driver_; }
  // <spec.name>.csv, .md and <spec.name>_<sensor>.{png,svg} (relative RMSE vs T with the
  // theory slopes).
  bool WriteReport(const SweepSpec& spec, const RunSummary& run,
                   const std::vector<PointStats>& stats, const ReportContext& context,
                   std::string* why) const override;

 private:
  CoefficientTrialDriver driver_;
};

}  // namespace allanlab::experiments
