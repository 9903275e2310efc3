#pragma once
// The kurtosis view's statistic (record_views.h, docs/theory.md §6.1): the excess kurtosis of the
// first differences of non-overlapping block means of m samples, ~0 for Gaussian noise of any
// spectrum. Computed for every m of a view at once: where m doubles, each block sum is the sum of
// two of the previous m's (pairwise summation), so all the octaves together cost O(N) rather than
// O(N) each. The statistic is scale-free, so it is taken on the block sums (the means times m).
#include <cstdint>
#include <span>
#include <vector>

namespace allanlab::experiments {

// One value per m of `ms` (ascending, each >= 1 and < rate.size() / 2); NaN where the increments
// do not vary.
std::vector<double> BlockIncrementKurtosis(std::span<const double> rate, std::span<const std::int64_t> ms);

// The excess kurtosis g2 = m4 / m2^2 - 3 of n values mapped to a normal deviate by Anscombe and
// Glynn's transform (Biometrika 70, 1983), exact in its first three moments for n iid Gaussian
// values: the view standardises this against its Monte Carlo envelope. g2 itself is right-skewed
// (skewness 0.87 at n = 255, the fewest increments the view takes), so its mean and sd put the
// upper tail in the wrong place: two of 103 independent controls read |z| 4.1 and 5.9 at the
// longest tau, where a calibrated view gives one such record in ~2000. NaN for n < 8 or NaN g2.
double KurtosisNormalDeviate(double excess_kurtosis, std::int64_t n);

}  // namespace allanlab::experiments
