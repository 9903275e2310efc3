#pragma once
// Bias and interval coverage of every Allan-family estimator with `allanlab avar`'s default
// intervals (--ci auto), on records made apart from sim/ (experiments/plain_noise.h) whose
// expectations are computed apart from the estimators (experiments/family_expectation.h).
//
// Statistics: AVAR, OAVAR, MVAR, HVAR, OHVAR, TOTVAR, TVAR (TDEV squared). Noises (unit scale):
//   white, flicker, random walk (point-sampled), quantization (differenced white angle), and a
//   composite: white + kCompositeFlicker x flicker + kCompositeRandomWalk x random walk, each
//   drawn from its own stream: white dominates below m ~ 8 (the flicker floor is ~4 before
//   scaling), flicker from there to m ~ 128, the random walk beyond.
// Taus: octave m = 1, 2, 4, ... with at least 8 clusters (m <= N/8) and within the statistic's
// reach (MaxAveragingFactor).
//
// Per trial, per noise id, statistic id and m (trial_driver.h conventions):
//   ratio/<noise>/<statistic>/m=<m>            estimate / E[estimate]
//   in_ci<level>/<noise>/<statistic>/m=<m>     1 when the chi-square interval at the default
//                                              EDF covers E[estimate]
// The spec's sensor only sets the sample rate and record length.
#include <cstdint>
#include <string>
#include <vector>

#include "estimators/statistic.h"
#include "experiments/experiment.h"

namespace allanlab::experiments {

// The composite record's flicker and random-walk scales (white has 1).
inline constexpr double kCompositeFlicker = 0.18;
inline constexpr double kCompositeRandomWalk = 0.054;

// The noises of the table, in order: "white", "flicker", "rw", "quantization", "composite".
const std::vector<std::string>& EstimatorCoverageNoises();
// The statistics of the table, in order.
const std::vector<estimators::Statistic>& EstimatorCoverageStatistics();

// One record of a noise of the table (n samples; a pure function of its arguments).
std::vector<double> EstimatorCoverageRecord(const std::string& noise, std::int64_t n,
                                            std::uint64_t seed, std::uint64_t stream);
// E[statistic(m)] for that noise on n samples with sample period tau0_s.
double EstimatorCoverageExpectation(const std::string& noise, estimators::Statistic statistic,
                                    std::int64_t m, std::int64_t n, double tau0_s);
// The averaging factors of a statistic on n samples: octave, >= 8 clusters, within its reach.
std::vector<std::int64_t> EstimatorCoverageFactors(estimators::Statistic statistic, std::int64_t n);

class EstimatorCoverageDriver : public TrialDriver {
 public:
  std::vector<std::string> Columns(const SweepSpec& spec, const SweepPoint& point) const override;
  std::unique_ptr<TrialWorkspace> MakeWorkspace() const override;
  std::vector<double> Run(const SweepSpec& spec, const SweepPoint& point, std::int64_t trial,
                          TrialWorkspace* workspace) const override;
};

class EstimatorCoverageExperiment : public DriverExperiment<EstimatorCoverageDriver> {
 public:
  std::string Name() const override { return "estimator_coverage"; }
  std::string Question() const override;
  // <spec.name>.csv (every cell) and .md (per statistic and noise: the median cell and the worst
  // one, with Wilson 95 % intervals and met / not met / undecided against nominal +- 2 points).
  bool WriteReport(const SweepSpec& spec, const RunSummary& run,
                   const std::vector<PointStats>& stats, const ReportContext& context,
                   std::string* why) const override;
};

}  // namespace allanlab::experiments
