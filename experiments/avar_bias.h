#pragma once
// The smallest real experiment: the bias of the Allan variance estimators against the exact
// expectation of the record (sim::SensorModel::ExpectedAvar), per tau. Also the golden set of
// `allanlab validate` (experiments/specs/validate/).
//
// Columns, per estimator of spec.estimators (overlapping and nonoverlapping only: those have an
// exact expectation in sim/) and per averaging factor m of spec.taus with m <= N/4:
//   avar_ratio/<estimator>/m=<m>   AVAR_hat(m) / E[AVAR_hat(m)]   (mean - 1 is the bias)
#include <cstdint>
#include <string>
#include <vector>

#include "experiments/experiment.h"
#include "experiments/injected_fault.h"

namespace allanlab::experiments {

class AvarBiasDriver : public FaultInjectableDriver {
 public:
  using FaultInjectableDriver::FaultInjectableDriver;
  std::vector<std::string> Columns(const SweepSpec& spec, const SweepPoint& point) const override;
  std::unique_ptr<TrialWorkspace> MakeWorkspace() const override;
  std::vector<double> Run(const SweepSpec& spec, const SweepPoint& point, std::int64_t trial,
                          TrialWorkspace* workspace) const override;
};

class AvarBiasExperiment : public DriverExperiment<AvarBiasDriver> {
 public:
  using DriverExperiment::DriverExperiment;
  std::string Name() const override { return "avar_bias"; }
  std::string Question() const override;
  bool WriteReport(const SweepSpec& spec, const RunSummary& run,
                   const std::vector<PointStats>& stats, const ReportContext& context,
                   std::string* why) const override;
};

}  // namespace allanlab::experiments
