#pragma once
// Sums of squared lag-m differences of a phase record x_0..x_n over all the start indices an
// estimator uses (order 2: x_{t+2m} - 2x_{t+m} + x_t, the Allan difference times m; order 3: the
// Hadamard one). Preconditions: phase.size() = n + 1, sums.size() = lags.size(), every lag
// 1 <= m with order * m <= n.
#include <cstdint>
#include <functional>
#include <span>

namespace allanlab::estimators {

class PhaseCheckpoints;

// Every start t = 0..n - order*m (OAVAR, OHVAR): n - order*m + 1 terms per lag.
// Cache-blocked passes serve all lags (see the .cc); extra memory O(lags), no allocation per lag.
void OverlappingDifferenceSums(std::span<const double> phase, int order,
                               std::span<const std::int64_t> lags, std::span<double> sums);

// The same sums from rate samples: fills phase (phase.size() = rate.size() + 1) as
// IntegrateAbout(rate, reference, phase) does, bit for bit, and sums the short lags right behind
// the integration while that part of the phase is still in cache, which saves a pass over it.
// When `phase_ready` is given, the rest of the pass (the long lags, which only read the phase) is
// handed to it as soon as the phase is complete: it must run that rest once, in any thread, before
// returning, and may do other work that reads the phase meanwhile.
using PhaseReady = std::function<void(const std::function<void()>& rest)>;
void IntegrateAndSumOverlappingDifferences(std::span<const double> rate, double reference,
                                           int order, std::span<const std::int64_t> lags,
                                           std::span<double> phase, std::span<double> sums,
                                           const PhaseReady* phase_ready = nullptr);

// Whether the lags suit the passes below: false when a lag of 32768 or more is not a multiple
// of its tier's row (dense or explicit grids; the octave grid always qualifies).
bool FitsCheckpointPass(std::int64_t n, int order, std::span<const std::int64_t> lags);

// The same sums without an N-sized phase: the phase is rebuilt in cache-sized pieces from the
// checkpoints of the integrated record (phase_checkpoints.h: N / 8 bytes), which spares the
// first touch of N + 1 fresh doubles. On long records a helper thread takes some of the pieces;
// their partial sums are added in a fixed order, so the bits are those of
// IntegrateAndSumOverlappingDifferences (rate x.rate(), reference x.reference()) in one thread or
// two. Returns false, with nothing computed, unless FitsCheckpointPass.
bool SumOverlappingDifferencesFromCheckpoints(const PhaseCheckpoints& x, int order,
                                              std::span<const std::int64_t> lags, std::span<double> sums);

// The same from the rate, checkpoints built here; *last_phase = x_N (not finite when the record
// is not).
bool SumOverlappingDifferencesFromRate(std::span<const double> rate, double reference, int order,
                                       std::span<const std::int64_t> lags, std::span<double> sums,
                                       double* last_phase);

// Starts t = 0, m, 2m, ... with t + order*m <= n (AVAR, HVAR): floor(n/m) - order + 1 terms.
void StridedDifferenceSums(std::span<const double> phase, int order,
                           std::span<const std::int64_t> lags, std::span<double> sums);

}  // namespace allanlab::estimators
