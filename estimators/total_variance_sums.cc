#include "estimators/total_variance_sums.h"

#include <algorithm>

#include "estimators/difference_kernel.h"

namespace allanlab::estimators {

void TotalVarianceSums(std::span<const double> phase, std::span<const std::int64_t> lags,
                       std::span<double> sums) {
  const auto n = static_cast<std::int64_t>(phase.size()) - 1;
  const double* x = phase.data();
  auto extended = [&](std::int64_t k) {
    if (k < 0) return 2.0 * x[0] - x[-k];
    if (k > n) return 2.0 * x[n] - x[2 * n - k];
    return x[k];
  };
  for (std::size_t j = 0; j < lags.size(); ++j) {
    const std::int64_t m = lags[j];
    // Centres whose neighbours both lie inside the record are ordinary second differences
    // starting at t = i - m; only the ends need the reflection.
    const std::int64_t inner_lo = std::max<std::int64_t>(1, m);
    const std::int64_t inner_hi = std::min(n - 1, n - m);  // inclusive
    CompensatedSum total;
    auto edge = [&](std::int64_t lo, std::int64_t hi) {  // centres lo..hi inclusive
      for (std::int64_t i = lo; i <= hi; ++i) {
        const double d = (extended(i - m) + extended(i + m)) - 2.0 * x[i];
        total.Add(d * d);
      }
    };
    if (inner_lo <= inner_hi) {
      total.Add(SumSquaredDifferences(x, 2, m, inner_lo - m, inner_hi - m + 1));
      edge(1, inner_lo - 1);
      edge(inner_hi + 1, n - 1);
    } else {
      edge(1, n - 1);
    }
    sums[j] = total.Value();
  }
}

}  // namespace allanlab::estimators
