#pragma once
// Validation table 2, `coefficient_recovery`: how well the slope method, WLS, log-WLS
// and GLS (estimators/fit/fit_avar_model.h) recover the IEEE 952 coefficients of a simulated
// sensor, per record length.
//
// Method: CoefficientTrialDriver (coefficient_trial.h) per trial; per point, method and
// coefficient present in the truth: relative bias and RMSE with Monte Carlo standard errors,
// empirical vs mean reported sigma, coverage of the reported 68.3 % / 95 % intervals with binomial
// errors, failure rate; for the slope method's B also the bias against what the curve minimum
// estimates, sqrt(B^2 + 2.617 N K) (docs/theory.md §4.2).
// Reference: the truth of the simulated model (B = the Kasdin flicker coefficient).
// Pass criterion (what the table is read for): a consistent method's RMSE shrinks with T and its
// coverage matches the nominal level within ~2 binomial errors; the slope method's error has a
// floor where terms overlap (docs/theory.md §4.5).
#include "experiments/coefficient_trial.h"
#include "experiments/experiment.h"

namespace allanlab::experiments {

class CoefficientRecoveryExperiment : public DriverExperiment<CoefficientTrialDriver> {
 public:
  using DriverExperiment::DriverExperiment;
  std::string Name() const override { return "coefficient_recovery"; }
  std::string Question() const override;
  // <spec.name>.csv, .md and <spec.name>_<sensor>_<coefficient>.{png,svg} (relative RMSE and
  // |bias| vs T).
  bool WriteReport(const SweepSpec& spec, const RunSummary& run,
                   const std::vector<PointStats>& stats, const ReportContext& context,
                   std::string* why) const override;
};

}  // namespace allanlab::experiments
