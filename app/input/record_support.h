#pragma once
// Whether a record is long enough for what a command asks of it. One rule for every command:
//
// An Allan variance at averaging factor m rests on about N/m independent clusters of the N
// samples. Below kMinClusters clusters its interval spans more than a factor of two in variance
// (7 degrees of freedom for white noise at 8 clusters, fewer for the random walks), so a tau
// above T/kMinClusters (T the record length) barely constrains anything. Hence:
//  - a fit of P parameters needs at least P + 1 octave taus (m = 1, 2, 4, ...) with at least
//    kMinClusters clusters each, i.e. N >= kMinClusters * 2^P samples; fewer is an error
//    (CheckRecordSupportsFit). Five IEEE terms need N >= 256; one term (N alone) needs 16.
//  - a fitted term whose share of the fitted curve exceeds half only at taus above
//    T/kMinClusters rests on those few clusters alone: its value is reported with a warning line
//    (WeaklySupportedTerms). This is how a rate ramp R "fitted" to 1 s of white noise is caught.
#include <cstdint>
#include <string>
#include <vector>

namespace allanlab::app {

inline constexpr std::int64_t kMinClusters = 8;

// Octave taus m = 1, 2, 4, ... with m <= samples / kMinClusters (0 when samples < kMinClusters).
int SupportedOctaveTaus(std::int64_t samples);

// Fails with one line (what the record gives, what the fit needs, the record length that would
// do, and how to ask less) when `samples` at `sample_rate_hz` cannot support `parameters` fitted
// parameters.
bool CheckRecordSupportsFit(std::int64_t samples, double sample_rate_hz, int parameters,
                            std::string* why);

// One fitted term's variance at each tau of the fitted curve.
struct FittedTermAvar {
  std::string name;          // "R", "K", "GM" ...
  std::vector<double> avar;  // same taus as the curve
};

// The warnings (one line each) for fitted terms that exceed half of the fitted total only at
// taus above samples / kMinClusters samples. `tau_s` and `m` are the curve's taus and averaging
// factors; every term's avar has their length.
std::vector<std::string> WeaklySupportedTerms(const std::vector<double>& tau_s,
                                              const std::vector<std::int64_t>& m,
                                              std::int64_t samples,
                                              const std::vector<FittedTermAvar>& terms);

}  // namespace allanlab::app
