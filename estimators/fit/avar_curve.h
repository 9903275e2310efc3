#pragma once
// An Allan-variance curve as the fits consume it: averaging factors, taus, values and EDFs of
// one estimator on one record, in SI (rad/s)^2.
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "common/sample_clock.h"
#include "estimators/avar_summary.h"
#include "sim/avar_theory.h"

namespace allanlab::estimators {

struct AvarCurve {
  SampleClock sample_clock;      // tau0 (default 1 s)
  std::int64_t num_samples = 0;  // N of the record the curve came from
  sim::AvarEstimatorKind estimator = sim::AvarEstimatorKind::kOverlapping;
  std::vector<std::int64_t> m;   // ascending averaging factors
  std::vector<double> tau_s;     // m * tau0
  std::vector<double> avar;      // (rad/s)^2, > 0
  std::vector<double> edf;       // equivalent degrees of freedom per tau (empty: unknown)

  std::size_t size() const { return m.size(); }
  // Sizes agree, m ascending and <= N/2, values finite and > 0, EDFs > 0 if given.
  bool IsValid(std::string* why) const;
};

// The points with min_tau_s <= tau <= max_tau_s (a manual tau range for a fit; record length
// and estimator kept, so GLS covariances stay those of the full record).
AvarCurve TauRange(const AvarCurve& curve, double min_tau_s, double max_tau_s);

// An overlapping-AVAR summary's points as a curve (its sample period and sample count): those with
// min_m <= m <= max_m and a positive value (a zero variance, from a constant stretch, cannot be
// fitted); an EDF the summary does not give (<= 0) becomes 1.
AvarCurve CurveFromSummary(const AvarSummary& summary, std::int64_t min_m = 1,
                           std::int64_t max_m = std::numeric_limits<std::int64_t>::max());

}  // namespace allanlab::estimators
