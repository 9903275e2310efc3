#pragma once
// Sums behind the total variance (NIST SP 1065 §5.2.11, Stable32, allantools `totdev`):
//   S(m) = sum_{i=1}^{n-1} (x*_{i-m} - 2 x_i + x*_{i+m})^2
// over phase x_0..x_n extended by reflection about both end points,
//   x*_{-j} = 2 x_0 - x_j,  x*_{n+j} = 2 x_n - x_{n-j}   (j = 1..n-1),
// so every tau keeps all n - 1 terms; TOTVAR(m) = S(m) / (2 m^2 (n - 1)) in rate units.
#include <cstdint>
#include <span>

namespace allanlab::estimators {

// Preconditions: phase.size() = n + 1 >= 3, sums.size() = lags.size(), 1 <= m <= n - 1.
void TotalVarianceSums(std::span<const double> phase, std::span<const std::int64_t> lags,
                       std::span<double> sums);

}  // namespace allanlab::estimators
