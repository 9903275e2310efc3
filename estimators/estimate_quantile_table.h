#pragma once
// The quantiles of EstimateQuantilesAt (estimators/estimate_distribution.h) that every default
// `avar` run asks for, read from a table instead of computed. Where m > kReducedAveragingFactor
// they depend only on the statistic, alpha, the reduced record's length and the confidence, and
// computing them (an eigen-solve and a few dozen Imhof quadratures per tau) costs more than the
// Allan pass of a 1e6-sample record. The table holds the overlapping AVAR at the default 68.3 %
// for alpha 0, -1 and -2 (the exponents the reduced record is used for) at every reduced length
// a point with at most kDistributionIntervalMaxClusters clusters has; its entries are the bits
// ComputeEstimateQuantiles gives (tests/tools/make_estimate_quantile_table.cc wrote them;
// tests/estimators/estimate_quantile_table_test.cc recomputes them).
#include <cstdint>
#include <optional>

#include "estimators/estimate_distribution.h"
#include "estimators/statistic.h"

namespace allanlab::estimators {

// The reduced record lengths the table covers: from the shortest with a term at m' (2 m') to
// the longest a point with at most kDistributionIntervalMaxClusters clusters reduces to.
inline constexpr std::int64_t kTabulatedShortestRecord = 2 * kReducedAveragingFactor;
inline constexpr std::int64_t kTabulatedLongestRecord =
    (kDistributionIntervalMaxClusters + 1) * kReducedAveragingFactor;
inline constexpr double kTabulatedConfidence = 0.683;

// EstimateQuantilesAt's result when the table holds it, else nothing (the caller computes).
std::optional<EstimateQuantiles> TabulatedEstimateQuantiles(Statistic s, int alpha, std::int64_t m,
                                                            std::int64_t n_rate, double confidence);

}  // namespace allanlab::estimators
