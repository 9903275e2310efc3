#pragma once
// Equivalent degrees of freedom of an Allan-family estimate measured on the record itself: the
// estimate is a mean of squared differences a_t (the d-th difference of the integrated record at
// lag m), and for Gaussian noise its EDF is
//   EDF = M / (1 + 2 sum_{k >= 1} (1 - k/M) rho_k^2),
// with M the number of terms averaged and rho_k the autocorrelation of the averaged terms at
// lag k. The terms of one estimate overlap only within d m samples of each other, so rho_k beyond
// lag d m comes from the noise alone and is small for every power law the estimators meet; the
// sum stops there. Unlike Greenhall & Riley's EDF (confidence.h), which models a continuous
// power-law process averaged over each sample interval, this needs neither the noise type nor the
// sampling model: at short taus a point-sampled random walk has 12 % more EDF at m = 8 than the
// averaged one (measured), and the record says which it is.
#include <cstdint>
#include <span>

#include "estimators/statistic.h"

namespace allanlab::estimators {

// The record-based EDF of statistic s at averaging factor m from the integrated record
// (phase.size() = n + 1, any reference level), or 0 when it is not available: for statistics
// other than AVAR, OAVAR, HVAR and OHVAR, or where the lag window d m is too long for the number
// of terms to measure the autocorrelations (RecordEdfAvailable). The autocorrelations are
// measured on at most max_terms consecutive differences from the middle of the record (bounded
// cost: O(max_terms d m)); their estimation bias (each rho_k^2 carries about S / M' of noise,
// S the sum above, M' the differences measured) is removed.
//
// The cap, 2^15 terms: what the measured autocorrelations add to the EDF grows with W / M' (W
// the lag window). At W = 256 (OAVAR at m = 128) a record's EDF scatters by about 6 % (rms, no
// visible bias; 3 % at W = 64), which moves an interval's half-width by about 3 % and its
// coverage by well under a point (tests/estimators/default_interval_coverage_stat_test.cc).
// The scatter falls as 1 / sqrt(M') (measured: ~1 % with 2^20 terms); 2^18 terms, at eight times
// the cost, cost more than the Allan pass itself on a record of 10^6 samples.
inline constexpr std::int64_t kRecordEdfMaxTerms = std::int64_t{1} << 15;
double RecordEdf(Statistic s, std::span<const double> phase, std::int64_t m,
                 std::int64_t max_terms = kRecordEdfMaxTerms);

// The stretch x_lo .. x_hi of the integrated record of n samples that RecordEdf reads at m (empty,
// hi < lo, where it gives 0), and RecordEdf from that stretch alone (stretch[i] = x_{lo + i}):
// the same bits, for a caller that rebuilds the stretch instead of keeping the whole record.
struct RecordEdfStretch {
  std::int64_t lo = 0, hi = -1;
};
RecordEdfStretch RecordEdfReads(Statistic s, std::int64_t n, std::int64_t m,
                                std::int64_t max_terms = kRecordEdfMaxTerms);
double RecordEdfFromStretch(Statistic s, std::int64_t n, std::span<const double> stretch,
                            std::int64_t m, std::int64_t max_terms = kRecordEdfMaxTerms);

// True when RecordEdf gives a value for s at m on n rate samples: the statistic is covered and
// the lag window d m is at most 1/64 of the differences measured (which keeps the removed bias
// under 4 % of the sum) and at most 256 lags (cost).
bool RecordEdfAvailable(Statistic s, std::int64_t m, std::int64_t n,
                        std::int64_t max_terms = kRecordEdfMaxTerms);

}  // namespace allanlab::estimators
