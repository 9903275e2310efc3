#pragma once
// Validation table 3: the seed paper's procedure (Mikheev et al. 2021) run on
// simulated records of its two gyros (presets mg25_mems and tg100), against the truth the
// records were generated from:
//   N = sigma(1 s) / 60 read off the curve, and from the -1/2 line (estimators/fit/slope_method.h);
//   B = min sigma / sqrt(2 ln2 / pi), which docs/theory.md §4.2 says reads sqrt(B^2 + 2.617 N K);
//   bandwidth from the short-tau ADEV maximum (estimators/fit/bandwidth_estimate.h), also with
//   the paper's rule "inflection tau = time constant" (fc = 1 / (2 pi tau_peak)).
// Per-trial columns (trial_driver.h): values in datasheet units (deg/sqrt(h), deg/h, Hz, s),
// ratios to the truth, 0/1 "found" indicators, and per tau the OAVAR ratio to its exact
// expectation with GR-interval coverage indicators (for the Allan diagram and coverage plot).
#include <string>
#include <vector>

#include "experiments/experiment.h"
#include "experiments/injected_fault.h"

namespace allanlab::experiments {

// The truth of a point's model in datasheet units (0 when the term is absent).
struct SeedPaperTruth {
  double n_deg_per_sqrt_h = 0.0;
  double b_deg_per_h = 0.0;
  double k_deg_per_h_per_sqrt_h = 0.0;
  double cutoff_hz = 0.0;          // 0 without a band-limit
  double b_floor_deg_per_h = 0.0;  // sqrt(B^2 + 2.617 N K): what the minimum reads (§4.2)
};
SeedPaperTruth TruthOf(const sim::SensorModel& model);

// Averaging factors: spec.taus candidates up to N/2 plus m = round(fs * 1 s) (the paper's
// reading point). Throws std::invalid_argument on a bad grid.
std::vector<std::int64_t> SeedPaperAveragingFactors(const SweepSpec& spec, const SweepPoint& point);

class SeedPaperDriver : public FaultInjectableDriver {
 public:
  using FaultInjectableDriver::FaultInjectableDriver;
  std::vector<std::string> Columns(const SweepSpec& spec, const SweepPoint& point) const override;
  std::unique_ptr<TrialWorkspace> MakeWorkspace() const override;
  std::vector<double> Run(const SweepSpec& spec, const SweepPoint& point, std::int64_t trial,
                          TrialWorkspace* workspace) const override;
};

class SeedPaperExperiment : public DriverExperiment<SeedPaperDriver> {
 public:
  using DriverExperiment::DriverExperiment;
  std::string Name() const override { return "seed_paper"; }
  std::string Question() const override;
  bool WriteReport(const SweepSpec& spec, const RunSummary& run,
                   const std::vector<PointStats>& stats, const ReportContext& context,
                   std::string* why) const override;
};

}  // namespace allanlab::experiments
