#pragma once
// Validation table 1: bias and error-bar accuracy of the Allan-family estimators on
// simulated records, against the exact theory of the record (sim::SensorModel::ExpectedAvar,
// estimators/exact_edf.h), per noise type, estimator and averaging factor m.
//
// Per trial and per (estimator, m) the driver writes (trial_driver.h conventions):
//   ratio/<est>/m=<m>            AVAR_hat / E[AVAR_hat]; for the estimators without an exact
//                                expectation in sim/ (modified, hadamard, total) the
//                                normaliser is E[OAVAR(m)] and the table reports no bias
//   edf_simple/<est>/m=<m>       K - 1, K = floor(N/m) clusters (seed paper, IEEE 952)
//   edf_gr/<est>/m=<m>           Greenhall-Riley EDF at the per-trial identified alpha
//                                (`allanlab avar --ci gr`; the default intervals are checked by
//                                default_intervals.h)
//   edf_exact/<est>/m=<m>        2 E^2 / Var from the model (docs/theory.md §3.1,
//                                estimators::ModelStatisticMoments); NaN for TOTVAR and for
//                                models with a non-Gaussian term (ramp, harmonic, ...)
//   in_ci<level>/<kind>/<est>/m=<m>  1 when the chi-square interval of that EDF kind at that
//                                level covers the exact expectation; NaN without one
// Records are rate samples of point.model, point.num_samples long; taus from spec.taus up to
// m <= N/4 (at least 4 clusters). The statistics are fixed: the five of the Allan family.
#include <string>
#include <vector>

#include "estimators/statistic.h"
#include "experiments/experiment.h"
#include "experiments/injected_fault.h"

namespace allanlab::experiments {

// The estimators the table covers, in table order.
const std::vector<estimators::Statistic>& ErrorBarStatistics();
// True when sim/ gives the exact expectation (and the exact EDF) of the statistic.
bool HasExactTheory(estimators::Statistic s);

class AvarErrorBarsDriver : public FaultInjectableDriver {
 public:
  using FaultInjectableDriver::FaultInjectableDriver;
  std::vector<std::string> Columns(const SweepSpec& spec, const SweepPoint& point) const override;
  std::unique_ptr<TrialWorkspace> MakeWorkspace() const override;
  std::vector<double> Run(const SweepSpec& spec, const SweepPoint& point, std::int64_t trial,
                          TrialWorkspace* workspace) const override;
};

// Averaging factors of a point: spec.taus candidates with 1 <= m <= N/4. Throws
// std::invalid_argument on a bad tau grid.
std::vector<std::int64_t> ErrorBarAveragingFactors(const SweepSpec& spec, const SweepPoint& point);

// "white (N)", "flicker (B)", "band-limited white (N, first-order 100 Hz)", "composite (Q+N+B+K)".
std::string NoiseLabel(const SweepPoint& point);

class AvarErrorBarsExperiment : public DriverExperiment<AvarErrorBarsDriver> {
 public:
  using DriverExperiment::DriverExperiment;
  std::string Name() const override { return "avar_error_bars"; }
  std::string Question() const override;
  bool WriteReport(const SweepSpec& spec, const RunSummary& run,
                   const std::vector<PointStats>& stats, const ReportContext& context,
                   std::string* why) const override;
};

}  // namespace allanlab::experiments
