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

}  // namespace allanlab::experiments
