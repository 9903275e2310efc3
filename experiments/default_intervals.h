#pragma once
// Coverage of `allanlab avar`'s default intervals (octave OAVAR, --ci auto) on records made apart
// from sim/ (experiments/plain_noise.h: white, flicker, point-sampled and averaged random walk),
// per octave tau with at least 8 clusters, at 68.3 % and 95 %; beside it the Greenhall-Riley
// intervals at the noise type identified at each tau alone (--ci gr, as Stable32).
//
// Per trial, per noise id and per averaging factor m (trial_driver.h conventions):
//   ratio/<noise>/m=<m>               OAVAR_hat / E[OAVAR_hat]
//   edf/<method>/<noise>/m=<m>        the EDF the method gave (method: auto, gr)
//   in_ci<level>/<method>/<noise>/m=<m>  1 when the interval covers E[OAVAR_hat]
// The sweep spec's sensor only sets the sample rate and the record length; the records are
// GeneratePlain's.
#include <string>
#include <vector>

#include "experiments/experiment.h"

namespace allanlab::experiments {

class DefaultIntervalsDriver : public TrialDriver {
 public:
  std::vector<std::string> Columns(const SweepSpec& spec, const SweepPoint& point) const override;
  std::unique_ptr<TrialWorkspace> MakeWorkspace() const override;
  std::vector<double> Run(const SweepSpec& spec, const SweepPoint& point, std::int64_t trial,
                          TrialWorkspace* workspace) const override;
};

// Octave averaging factors with at least 8 clusters: 1, 2, 4, ..., m <= N/8.
std::vector<std::int64_t> DefaultIntervalFactors(std::int64_t num_samples);

class DefaultIntervalsExperiment : public DriverExperiment<DefaultIntervalsDriver> {
 public:
  std::string Name() const override { return "default_intervals"; }
  std::string Question() const override;
  bool WriteReport(const SweepSpec& spec, const RunSummary& run,
                   const std::vector<PointStats>& stats, const ReportContext& context,
                   std::string* why) const override;
};

}  // namespace allanlab::experiments
