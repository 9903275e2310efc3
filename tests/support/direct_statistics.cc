#include "tests/support/direct_statistics.h"

#include <vector>

namespace allanlab::testing_support {
namespace {

using estimators::Statistic;
using Real = long double;

// Mean of rate[t .. t+m-1] from a long-double running sum (64-bit mantissa: at the record
// lengths tested here it keeps ~1e-14 of a cluster sum; the code under test works in double).
class ClusterMeans {
 public:
  explicit ClusterMeans(std::span<const double> y) : sum_(y.size() + 1, 0) {
    for (std::size_t k = 0; k < y.size(); ++k) sum_[k + 1] = sum_[k] + y[k];
  }
  Real operator()(std::int64_t t, std::int64_t m) const { return (sum_[t + m] - sum_[t]) / m; }

 private:
  std::vector<Real> sum_;
};

// Allan (order 2: ybar_{t+m} - ybar_t) or Hadamard (order 3: ybar_{t+2m} - 2 ybar_{t+m} +
// ybar_t) variance over starts t = 0, stride, 2 stride, ...
Real ClusterVariance(std::span<const double> y, std::int64_t m, int order, std::int64_t stride) {
  const ClusterMeans mean(y);
  const auto n = static_cast<std::int64_t>(y.size());
  const std::int64_t span = order == 2 ? 2 * m : 3 * m;
  Real sum = 0;
  std::int64_t terms = 0;
  for (std::int64_t t = 0; t + span <= n; t += stride, ++terms) {
    const Real d = order == 2 ? mean(t + m, m) - mean(t, m)
                              : mean(t + 2 * m, m) - 2 * mean(t + m, m) + mean(t, m);
    sum += d * d;
  }
  return sum / ((order == 2 ? 2 : 6) * static_cast<Real>(terms));
}

std::vector<Real> Phase(std::span<const double> y, double tau0) {
  std::vector<Real> x(y.size() + 1, 0);
  for (std::size_t k = 0; k < y.size(); ++k) x[k + 1] = x[k] + static_cast<Real>(y[k]) * tau0;
  return x;
}

// SP 1065: MVAR = 1/(2 m^2 tau^2 (N-3m+1)) sum_j (sum_{i=j}^{j+m-1} x_{i+2m} - 2x_{i+m} + x_i)^2,
// N phase points.
Real ModifiedAllan(std::span<const double> y, std::int64_t m, double tau0) {
  const std::vector<Real> x = Phase(y, tau0);
  const auto np = static_cast<std::int64_t>(x.size());
  Real sum = 0;
  for (std::int64_t j = 0; j + 3 * m <= np; ++j) {  // reads up to x_{j+3m-1}
    Real inner = 0;
    for (std::int64_t i = j; i < j + m; ++i) inner += x[i + 2 * m] - 2 * x[i + m] + x[i];
    sum += inner * inner;
  }
  const Real tau = static_cast<Real>(m) * tau0;
  return sum / (2 * static_cast<Real>(m) * m * tau * tau * (np - 3 * m + 1));
}

// SP 1065 §5.2.11 / allantools totdev: phase extended by N-2 reflected points at each end.
Real Total(std::span<const double> y, std::int64_t m, double tau0) {
  const std::vector<Real> x = Phase(y, tau0);
  const auto np = static_cast<std::int64_t>(x.size());
  std::vector<Real> ext;
  for (std::int64_t j = np - 2; j >= 1; --j) ext.push_back(2 * x[0] - x[j]);
  const std::int64_t offset = static_cast<std::int64_t>(ext.size());
  for (Real v : x) ext.push_back(v);
  for (std::int64_t j = 1; j <= np - 2; ++j) ext.push_back(2 * x[np - 1] - x[np - 1 - j]);
  Real sum = 0;
  for (std::int64_t i = 1; i <= np - 2; ++i) {
    const Real d = ext[offset + i - m] - 2 * ext[offset + i] + ext[offset + i + m];
    sum += d * d;
  }
  const Real tau = static_cast<Real>(m) * tau0;
  return sum / (2 * tau * tau * (np - 2));
}

}  // namespace

long double DirectStatistic(Statistic s, std::span<const double> rate, std::int64_t m,
                            double tau0_s) {
  switch (s) {
    case Statistic::kAllanNonOverlapping:
      return ClusterVariance(rate, m, 2, m);
    case Statistic::kAllanOverlapping:
      return ClusterVariance(rate, m, 2, 1);
    case Statistic::kModifiedAllan:
      return ModifiedAllan(rate, m, tau0_s);
    case Statistic::kHadamardNonOverlapping:
      return ClusterVariance(rate, m, 3, m);
    case Statistic::kHadamardOverlapping:
      return ClusterVariance(rate, m, 3, 1);
    case Statistic::kTotal:
      return Total(rate, m, tau0_s);
    case Statistic::kTime: {
      const Real tau = static_cast<Real>(m) * tau0_s;
      return tau * tau * ModifiedAllan(rate, m, tau0_s) / 3;
    }
  }
  return 0;
}

}  // namespace allanlab::testing_support
