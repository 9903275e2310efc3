#pragma once
// Equivalent degrees of freedom and confidence intervals of Allan-family estimates.
#include <cstdint>

#include "estimators/statistic.h"

namespace allanlab::estimators {

// Greenhall & Riley (2003 PTTI), "Uncertainty of stability variances based on finite
// differences" (docs/theory.md §3.4), as Stable32 and allantools implement it. alpha in -4..2,
// d in {1, 2, 3}, m >= 1, n_phase = number of phase points (rate samples + 1).
// Returns 0 when the inputs are outside the algorithm's domain (alpha + 2d <= 1).
double GreenhallRileyEdf(int alpha, int d, std::int64_t m, std::int64_t n_phase, bool overlapping,
                         bool modified);

// TOTVAR EDF, NIST SP 1065 Table 7: b (T/tau) - c for alpha = 0, -1, -2 (T = record length).
double TotalVarianceEdf(int alpha, double record_length_s, double tau_s);

// EDF for a statistic at averaging factor m on n_rate rate samples (dispatches to the above;
// TOTVAR at alpha = 1, 2, outside Table 7, uses SP 1065 Table 5's simple formulas, as Stable32).
double StatisticEdf(Statistic s, int alpha, std::int64_t m, std::int64_t n_rate, double tau0_s);

// TOTVAR EDF for `allanlab avar`'s default intervals (--ci auto): total_edf (StatisticEdf's, SP
// 1065), but at most oavar_edf, the EDF of the overlapping AVAR at the same m, scaled by the number
// of terms, (n_rate - 1) / (n_rate - 2m + 1). TOTVAR's centres from m to n - m are OAVAR's
// differences and the other 2m - 2 repeat record samples through the reflection; at m = 1 the two
// statistics are the same number, where SP 1065's b T/tau (fitted for tau >> tau0) gives 1.9
// times OAVAR's EDF for white FM (records of 512 samples: 68.3 % intervals covered 0.48). The
// bound binds at the shortest taus only (m <= 4 for 4096 samples).
double BoundTotalVarianceEdf(double total_edf, double oavar_edf, std::int64_t m, std::int64_t n_rate);

// The seed paper's / IEEE 952 simple error: EDF = K - 1 for K non-overlapping clusters
// (sigma(delta)/sigma = 1/sqrt(2(K-1))).
double SimpleEdf(std::int64_t clusters);

struct Interval {
  double low = 0.0, high = 0.0;
};
// Two-sided chi-square interval for a variance estimate with `edf` degrees of freedom at
// `confidence` (Stable32 convention, docs/theory.md §3.5): [v edf/chi2_{1-p}, v edf/chi2_{p}],
// p = (1 - confidence)/2.
Interval ChiSquareInterval(double variance, double edf, double confidence);

}  // namespace allanlab::estimators
