#pragma once
// The phase (angle) record behind rate samples, which is how NIST SP 1065 writes every
// Allan-family statistic: x_0 = 0, x_{k+1} = x_k + (y_k - reference), k = 0..N-1, in units of
// rate x tau0 (tau0 = 1; the statistics scale it back).
//
// Why a reference: every statistic is a difference of order >= 2 of x (or a sum of such), so a
// constant offset of y - a linear drift of x - cancels exactly. It only has to be removed so
// that |x| stays near the noise excursion and the differences keep their digits: with a rate
// bias of 1e4 x the noise on 1e7 samples, the raw integral would be ~1e11 x the noise and a
// second difference would keep ~5 of its 16 digits. Any level within a few noise standard
// deviations of the mean does; the statistics use ReferenceLevel, which costs no extra pass
// over a long record.
#include <cstddef>
#include <span>

namespace allanlab::estimators {

// Mean of the samples: lanes per block of 4096, blocks added with compensation (a few 1e-15
// relative; any error is a drift of the phase that the statistics cancel). NaN or infinite
// when a sample is, or when finite samples overflow the sum.
double MeanOf(std::span<const double> values);

// The mean of at most kReferenceSamples samples spread evenly over the record (every
// ceil(N / kReferenceSamples)-th one). Like the record mean it follows slow wander and warm-up
// transients, so the integral about it stays as small as about the mean (within ~sigma/256 of it
// for white noise), and reads one cache line per stride: next to nothing on a long record.
inline constexpr std::size_t kReferenceSamples = 65536;
double ReferenceLevel(std::span<const double> values);

// out[k+1] = out[k] + (values[k] - reference) for k = 0..values.size()-1, starting from the
// out[0] the caller left there. out.size() == values.size() + 1.
// Vectorised (the running sum is a dependency chain otherwise): additions are grouped eight at a
// time from values[0], so an integral built in pieces that start at multiples of 8 has the same
// bits as one built in one call.
void ContinueIntegral(std::span<const double> values, double reference, std::span<double> out);

// out[0] = 0, then ContinueIntegral.
void IntegrateAbout(std::span<const double> values, double reference, std::span<double> out);

// The phase of a rate record with its mean removed: IntegrateAbout(rate, MeanOf(rate), phase).
void IntegrateMeanRemoved(std::span<const double> rate, std::span<double> phase);

}  // namespace allanlab::estimators
