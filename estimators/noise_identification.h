#pragma once
// Power-law noise identification per tau (Riley & Greenhall 2004, "Power law noise
// identification using the lag 1 autocorrelation"; NIST SP 1065 §5.6), with the B1 ratio
// (Barnes) as fallback when too few points remain. alpha: S_y(f) ~ f^alpha, rate as frequency.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <span>

namespace allanlab::estimators {

struct NoiseId {
  int alpha = 0;           // rounded exponent, clamped to [-2, 2]
  bool identified = false;  // false if neither method could run
  bool used_b1 = false;     // the B1 ratio fallback was used
  // The exponent before rounding and clamping (-2 (delta + d) for the lag-1 ACF, the B1 ratio's
  // mu inverted for B1; 2 or 1 exactly where R(n) decided between the phase noises), and the
  // number of m-averages it came from: the estimate's standard error is about 2 / sqrt(averages)
  // for the ACF at the white end and grows for the B1 ratio. NaN when !identified.
  double estimate = std::numeric_limits<double>::quiet_NaN();
  std::int64_t averages = 0;
};

// Identification at averaging factor m from rate samples (the lag-1 ACF of m-averaged, and if
// needed differenced, rates). Needs at least about 30 averaged points for the ACF method.
NoiseId IdentifyNoise(std::span<const double> rate, std::int64_t m);

// The same from the integrated record as well (phase[k] = sum_{i<k} (rate_i - c) for any constant
// c, N + 1 values): the m-averages come from phase differences in O(N/m) instead of O(N), so a
// whole curve costs O(N) rather than O(N) per tau. Same result up to rounding.
NoiseId IdentifyNoise(std::span<const double> rate, std::span<const double> phase, std::int64_t m);

// The same from the integrated record sampled at every m-th index alone: sampled[k] = phase[k m],
// k = 0..count, for count m-averages. modified_to_allan_ratio() is called only where the B1
// ratio cannot tell white FM from the phase noises (a few averages), and must give
// ModifiedToAllanRatioOfPhase of the record's whole integrated record: then the result is
// IdentifyNoise's with that record, bit for bit, without the record in memory.
NoiseId IdentifyNoiseFromSampledPhase(std::span<const double> sampled, std::int64_t m,
                                      const std::function<double()>& modified_to_allan_ratio);

// Identification from the integrated record keeps up to `count` m-averages in memory for its
// passes (default 2^20) and recomputes more in every pass: the same bits either way. Sets the
// limit and returns the previous one, so that a test can compare the two; not thread-safe.
std::size_t SetMaxStoredAveragesForTesting(std::size_t count);

// R(n) = MVAR(m) / OAVAR(m) of a record from its integrated record (phase.size() = N + 1), as
// identification computes it.
double ModifiedToAllanRatioOfPhase(std::span<const double> phase, std::int64_t m);
// The same for the stretch x_first .. x_{first + length} of an integrated record kept as
// checkpoints, rebuilt a few thousand values at a time: the same bits, in O(m) memory.
class PhaseCheckpoints;
double ModifiedToAllanRatioOfCheckpoints(const PhaseCheckpoints& x, std::int64_t first, std::int64_t length,
                                         std::int64_t m);

}  // namespace allanlab::estimators
