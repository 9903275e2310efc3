#pragma once
// The smallest real experiment: the bias of the Allan variance estimators against the exact
// expectation of the record (sim::SensorModel::ExpectedAvar), per tau. Also the golden set of
// `allanlab validate` (experiments/specs/validate/).
//
// Columns, per estimator of spec.estimators (overlapping and nonoverlapping only: those have an
// exact expectation in sim/) and per averaging factor m of spec.taus with m <= N/4:
//   avar_ratio/<estimator>/m=<m>   AVAR_hat(m) / E[AVAR_hat(m)]   (mean - 1 is the bias)
// Test hook: ALLANLAB_INJECT_AVAR_SCALE (experiments/injected_fault.h) multiplies every estimate.
#include <cstdint>
#include <string>
#include <vector>

#include "experiments/experiment.h"

namespace allanlab::experiments {

class AvarBiasDriver : public TrialDriver {
 public:
  std::vector<std::string> Columns(const SweepSpec& spec, const SweepPoint& point) const override;
  std::unique_ptr<TrialWorkspace> MakeWorkspace() const override;
  std::vector<double> Run(const SweepSpec& spec, const SweepPoint& point, std::int64_t trial,
                          TrialWorkspace* workspace) const override;
};

class AvarBiasExperiment : public Experiment {
 public:
  std::string Name() const override { return "avar_bias"; }
  std::string Question() const override;
  const TrialDriver& Driver() const override { return driver_; }
  bool WriteReport(const SweepSpec& spec, const RunSummary& run,
                   const std::vector<PointStats>& stats, const ReportContext& context,
                   std::string* why) const override;

 private:
  AvarBiasDriver driver_;
};

}  // namespace allanlab::experiments
