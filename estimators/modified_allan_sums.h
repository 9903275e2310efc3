#pragma once
// Sums behind the modified Allan variance (NIST SP 1065 eq. 14, phase form):
//   S(m) = sum_{j=0}^{n+1-3m} ( sum_{i=j}^{j+m-1} (x_{i+2m} - 2 x_{i+m} + x_i) )^2
// over phase x_0..x_n, n - 3m + 2 terms; MVAR(m) = S(m) / (2 m^4 (n - 3m + 2)) in rate units.
#include <cstdint>
#include <span>

namespace allanlab::estimators {

// Doubles of work space ModifiedAllanSums needs for these lags (at most n).
std::int64_t ModifiedAllanWorkSize(std::int64_t n, std::span<const std::int64_t> lags);

// Preconditions: phase.size() = n + 1, sums.size() = lags.size(), 1 <= m, 3m <= n + 1,
// work.size() >= ModifiedAllanWorkSize(n, lags).
void ModifiedAllanSums(std::span<const double> phase, std::span<const std::int64_t> lags,
                       std::span<double> work, std::span<double> sums);

}  // namespace allanlab::estimators
