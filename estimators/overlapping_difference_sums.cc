#include <algorithm>
#include <numeric>
#include <vector>

#include "estimators/difference_kernel.h"
#include "estimators/difference_sums.h"

namespace allanlab::estimators {
namespace {

// Start indices per block. A lag-m term reads x_t, x_{t+m}, x_{t+2m}: one block of all lags
// touches the block itself plus the blocks m and 2m ahead. Blocking by t (rather than one pass
// per lag) reads x from memory once for all lags whose look-ahead fits in cache, instead of once
// per lag; a plain per-lag loop is memory bound on long records.
constexpr std::int64_t kBlock = 2048;

}  // namespace

void OverlappingDifferenceSums(std::span<const double> phase, int order,
                               std::span<const std::int64_t> lags, std::span<double> sums) {
  const auto n = static_cast<std::int64_t>(phase.size()) - 1;
  const double* x = phase.data();
  const std::size_t count = lags.size();
  if (count == 0) return;

  // Ascending lags have descending term counts, so a block can stop at the first lag it is past.
  std::vector<std::size_t> by_lag(count);
  std::iota(by_lag.begin(), by_lag.end(), std::size_t{0});
  std::stable_sort(by_lag.begin(), by_lag.end(),
                   [&](std::size_t a, std::size_t b) { return lags[a] < lags[b]; });
  std::vector<std::int64_t> m(count), end(count);
  for (std::size_t j = 0; j < count; ++j) {
    m[j] = lags[by_lag[j]];
    end[j] = n - order * m[j] + 1;
  }
  std::vector<Lanes> lanes(count, Lanes{});
  std::vector<CompensatedSum> totals(count);
  auto flush = [&](std::size_t j) {
    totals[j].Add(SumLanes(lanes[j]));
    lanes[j] = Lanes{};
  };

  for (std::int64_t start = 0; start < end[0]; start += kBlock) {
    const std::int64_t stop = start + kBlock;
    for (std::size_t j = 0; j < count && start < end[j]; ++j) {
      const std::int64_t e = std::min(stop, end[j]);
      const bool pair = order == 2 && j + 1 < count && m[j + 1] == 2 * m[j] && start < end[j + 1];
      if (pair) {
        const std::int64_t e2 = std::min(stop, end[j + 1]);
        AccumulateSquaredSecondDifferencesPair(x, m[j], start, e2, &lanes[j], &lanes[j + 1]);
        AccumulateSquaredDifferences(x, order, m[j], e2, e, &lanes[j]);
        flush(j);
        flush(++j);
      } else {
        AccumulateSquaredDifferences(x, order, m[j], start, e, &lanes[j]);
        flush(j);
      }
    }
  }
  for (std::size_t j = 0; j < count; ++j) sums[by_lag[j]] = totals[j].Value();
}

}  // namespace allanlab::estimators
