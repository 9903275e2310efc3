#pragma once
// Allan variance of rate (frequency) samples: overlapping (IEEE Std 1554 recommendation) and
// non-overlapping (IEEE Std 952 Annex C; seed paper eq. 2) estimators.
//   AVAR(m) = 1/(2 T) sum_t (ybar_{t+m} - ybar_t)^2, ybar_t = mean of y_t..y_{t+m-1},
// over t = 0..N-2m (overlapping, T = N-2m+1) or t = 0, m, 2m, ... (non-overlapping, T = M-1).
#include <cstdint>
#include <span>
#include <vector>

#include "sim/avar_theory.h"

namespace allanlab::estimators {

using sim::AvarEstimatorKind;

// AVAR at each averaging factor in `ms` (each 1 <= m <= N/2), in the squared units of `rate`.
// One prefix sum of the record about a level near its mean serves all m (the level is removed
// so that a large bias does not eat the digits of the differences; phase_integral.h), summed in
// the cache-blocked passes of allan_family.h. Throws std::invalid_argument for an m out of
// range.
std::vector<double> AllanVariance(std::span<const double> rate, std::span<const std::int64_t> ms,
                                  AvarEstimatorKind kind);

// m = 1, 2, 4, ... while m <= max_m.
std::vector<std::int64_t> OctaveAveragingFactors(std::int64_t max_m);

}  // namespace allanlab::estimators
