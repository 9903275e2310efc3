#pragma once
// The phase (angle) record behind rate samples, which is how NIST SP 1065 writes every
// Allan-family statistic: x_0 = 0, x_{k+1} = x_k + (y_k - reference), k = 0..N-1, in units of
// rate x tau0 (tau0 = 1; the statistics scale it back).
//
// Why a reference: every statistic is a difference of order >= 2 of x (or a sum of such), so a
// constant offset of y - a linear drift of x - cancels exactly. It only has to be removed so
// that |x| stays near the noise excursion and the differences keep their digits: with a rate
// bias of 1e4 x the noise on 1e7 samples, the raw integral would be ~1e11 x the noise and a
// second difference would keep ~5 of its 16 digits.
#include <span>

namespace allanlab::estimators {

// Mean of the samples, accumulated in independent lanes with a compensated total.
double MeanOf(std::span<const double> values);

// out[0] = 0, out[k+1] = out[k] + (values[k] - reference). out.size() == values.size() + 1.
// Vectorised (the running sum is a dependency chain otherwise): the additions are grouped
// differently from a plain loop, which changes x only by rounding.
void IntegrateAbout(std::span<const double> values, double reference, std::span<double> out);

// The phase of a rate record with its mean removed: IntegrateAbout(rate, MeanOf(rate), phase).
void IntegrateMeanRemoved(std::span<const double> rate, std::span<double> phase);

}  // namespace allanlab::estimators
