#pragma once
// Parametric bootstrap of a fit's uncertainties: simulate the fitted model at the record's length
// and rate (sim::SensorModel::Generate), recompute the same Allan curve (same averaging factors,
// same estimator), refit it, and take the spread of the refitted values as the standard
// uncertainty. Needed where the covariance sigma (S' W S)^-1 is wrong because the weight matrix
// misdescribes the estimates: a random-phase sinusoid is not Gaussian and is not in Omega
// (parametric_recovery_stat_test.cc: its amplitude's covariance sigma is ~4x too small).
// The replicates are conditional on the fit's choices: the same terms (those the fit kept), the
// same method, and the original curve's EDFs as weights (the EDF is a property of the estimator
// at these taus, not re-identified per replicate). Determinism: replicate r simulates
// Generate(seed, r, N); replicates run in parallel (OpenMP) into their own slots and are reduced
// in replicate order, so the result is bit-identical for any thread count.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "estimators/fit/avar_curve.h"
#include "sim/sensor_model.h"

namespace allanlab::estimators {

struct BootstrapOptions {
  int trials = 100;            // replicates; >= 2 (sigma from trials - 1 degrees of freedom)
  std::uint64_t seed = 1;      // replicate r draws Generate(seed, r, N)
  bool IsValid(std::string* why) const;
};

struct BootstrapSpread {
  int trials = 0;              // replicates simulated
  int used = 0;                // replicates whose refit succeeded (the statistics below)
  std::vector<double> mean;    // per parameter, in the refit's order
  std::vector<double> sigma;   // sample standard deviation (divisor used - 1)
  std::string first_failure;   // message of the first failed refit (replicate order), if any
};

// Fills `values` (fixed length, one entry per parameter) from a fit of the replicate curve;
// returns false with a message on failure. Called concurrently from several threads: it must
// only read shared state.
using BootstrapRefit =
    std::function<bool(const AvarCurve& replicate, std::vector<double>* values, std::string* why)>;

// Preconditions: options.IsValid(), model.IsValid(), curve.IsValid() with num_samples > 0.
// `parameters` is the length of every values vector.
BootstrapSpread ParametricBootstrap(const sim::SensorModel& model, const AvarCurve& curve,
                                    const BootstrapOptions& options, std::size_t parameters,
                                    const BootstrapRefit& refit);

}  // namespace allanlab::estimators
