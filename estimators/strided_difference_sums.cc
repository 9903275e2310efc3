#include "estimators/difference_kernel.h"
#include "estimators/difference_sums.h"

namespace allanlab::estimators {

void StridedDifferenceSums(std::span<const double> phase, int order,
                           std::span<const std::int64_t> lags, std::span<double> sums) {
  const auto n = static_cast<std::int64_t>(phase.size()) - 1;
  const double* x = phase.data();
  for (std::size_t j = 0; j < lags.size(); ++j) {
    const std::int64_t m = lags[j];
    const std::int64_t count = n / m - order + 1;
    CompensatedSum total;
    Lanes lanes{};
    for (std::int64_t k = 0; k < count; ++k) {
      const double* p = x + k * m;
      const double d = order == 2 ? (p[0] + p[2 * m]) - (p[m] + p[m])
                                  : (p[3 * m] - p[0]) - 3.0 * (p[2 * m] - p[m]);
      lanes[k % kLanes] += d * d;
      // Flush often enough that no lane holds a long running sum.
      if (k % 4096 == 4095) {
        total.Add(SumLanes(lanes));
        lanes = {};
      }
    }
    total.Add(SumLanes(lanes));
    sums[j] = total.Value();
  }
}

}  // namespace allanlab::estimators
