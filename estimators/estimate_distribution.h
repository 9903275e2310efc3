#pragma once
// The distribution of an Allan-family estimate where chi-square(EDF) is too coarse: at few clusters
// (docs/theory.md §3.5.1). An estimate that averages squared differences of Gaussian noise is a
// quadratic form, V_hat / E[V_hat] = sum_i w_i X_i with X_i independent chi-square(1) and
// w_i >= 0, sum w_i = 1 (the eigenvalues of the differences' covariance over their count, divided
// by its trace). chi-square(EDF) matches its first two moments only: with 8 clusters of white
// rate noise (OAVAR, EDF 9.7) its 68.3 % and 95 % intervals cover 0.71 and 0.96, where these
// weights' own quantiles give the nominal levels.
#include <cstdint>
#include <span>
#include <vector>

#include "estimators/statistic.h"

namespace allanlab::estimators {

// Averaging factor of the reduced record on which the weights are computed. The weights depend on
// m and N almost only through the cluster count N/m once m is large: at 8 clusters the 2.5 %,
// 15.9 %, 84.1 % and 97.5 % quantiles for m' = 16 and m' = 32 agree within 0.5 % for white and
// random-walk rate noise (docs/theory.md §3.5.1).
inline constexpr std::int64_t kReducedAveragingFactor = 16;

// `avar --ci auto` takes its interval from these weights at up to this many clusters N/m; beyond,
// chi-square(EDF) is within about a point of the nominal levels (docs/theory.md §3.5.1).
inline constexpr std::int64_t kDistributionIntervalMaxClusters = 16;

// Weights w (sum 1, descending) of V_hat / E[V_hat] for statistic s at averaging factor m on
// n_rate rate samples under power-law rate noise of exponent alpha (0 white, -1 flicker, -2
// random walk, 2 white phase, 1 flicker phase), computed on a record of round(n_rate m' / m)
// samples at m' = kReducedAveragingFactor when m > m' (the actual record otherwise). Empty when
// the statistic has no exact moments (TOTVAR, TVAR), alpha is outside -2..2, m is out of range,
// the record would be reduced for phase noise (alpha > 0: its differences decorrelate within a lag
// or two, so the distribution depends on N, not N/m, and its EDF is large: chi-square fits), or
// the reduced record has more than max_terms differences (the eigen-solve grows as its cube).
std::vector<double> EstimateWeights(Statistic s, int alpha, std::int64_t m, std::int64_t n_rate,
                                    std::int64_t max_terms = 512);

// P(sum w_i X_i <= x) for X_i independent chi-square(1) and w_i >= 0 (Imhof 1961, the inversion
// of the characteristic function, by adaptive Gauss-Kronrod quadrature; absolute error ~1e-8).
double WeightedChiSquareCdf(std::span<const double> weights, double x);

// The p-quantile (0 < p < 1) of the same distribution.
double WeightedChiSquareQuantile(std::span<const double> weights, double p);

// The (1 - confidence) / 2 and (1 + confidence) / 2 quantiles of V_hat / E[V_hat] for
// EstimateWeights(s, alpha, m, n_rate), the weights past the 24 largest lumped in four groups of
// matched mean and variance (quantiles within 1e-3 relative of the unlumped ones at 16 clusters,
// at a tenth of the cost); ok = false when those weights are empty. The calling
// thread keeps its last results (a Monte Carlo sweep asks for the same record shape thousands of
// times; each costs an eigen-solve and a few dozen quadratures).
struct EstimateQuantiles {
  bool ok = false;
  double low = 0.0, high = 0.0;
};
EstimateQuantiles EstimateQuantilesAt(Statistic s, int alpha, std::int64_t m, std::int64_t n_rate,
                                      double confidence);

// The same quantiles always computed (no table, estimators/estimate_quantile_table.h, and no
// remembered results): what the table was made from and is checked against.
EstimateQuantiles ComputeEstimateQuantiles(Statistic s, int alpha, std::int64_t m, std::int64_t n_rate,
                                           double confidence);

// The length of the reduced record EstimateWeights computes on when m > kReducedAveragingFactor:
// round(n_rate m' / m).
std::int64_t ReducedRecordLength(std::int64_t m, std::int64_t n_rate);

}  // namespace allanlab::estimators
