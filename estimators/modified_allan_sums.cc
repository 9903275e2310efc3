#include "estimators/modified_allan_sums.h"

#include <algorithm>

#include "estimators/difference_kernel.h"

namespace allanlab::estimators {
namespace {

// Inner sums per block are at least this many, so restarting the running sum is cheap.
constexpr std::int64_t kMinBlock = 4096;

std::int64_t BlockLength(std::int64_t m, std::int64_t terms) {
  return std::min(std::max(kMinBlock, 3 * m), terms);
}

}  // namespace

// The inner sum of m second differences d_i = x_{i+2m} - 2x_{i+m} + x_i is a first difference
// of their running sum Q: sum_{i=j}^{j+m-1} d_i = Q_{j+m} - Q_j. Q is taken over the second
// differences, not over x (the textbook third difference of the double integral of y): a rate
// offset or drift is already gone from d, whereas a double integral grows like n^2 times it and
// leaves too few digits for the difference. Q restarts every block, so it sums a few thousand
// terms at most.
std::int64_t ModifiedAllanWorkSize(std::int64_t n, std::span<const std::int64_t> lags) {
  std::int64_t size = 0;
  for (std::int64_t m : lags) size = std::max(size, BlockLength(m, n - 3 * m + 2) + m);
  return size;
}

void ModifiedAllanSums(std::span<const double> phase, std::span<const std::int64_t> lags,
                       std::span<double> work, std::span<double> sums) {
  const auto n = static_cast<std::int64_t>(phase.size()) - 1;
  const double* x = phase.data();
  double* running = work.data();
  for (std::size_t k = 0; k < lags.size(); ++k) {
    const std::int64_t m = lags[k];
    const std::int64_t terms = n - 3 * m + 2;
    const std::int64_t block = BlockLength(m, terms);
    CompensatedSum total;
    for (std::int64_t j0 = 0; j0 < terms; j0 += block) {
      const std::int64_t len = std::min(block, terms - j0);
      // Q_0 .. Q_{len+m-1} over d_{j0} .. d_{j0+len+m-2}; the last d reads x_{j0+len+3m-2} <= x_n.
      double q = 0.0;
      running[0] = 0.0;
      for (std::int64_t i = 0; i + 1 < len + m; ++i) {
        const double* p = x + j0 + i;
        q += (p[0] + p[2 * m]) - (p[m] + p[m]);
        running[i + 1] = q;
      }
      Lanes lanes{};
      AccumulateSquaredDifferences(running, 1, m, 0, len, &lanes);
      total.Add(SumLanes(lanes));
    }
    sums[k] = total.Value();
  }
}

}  // namespace allanlab::estimators
