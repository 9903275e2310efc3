#include "estimators/exact_quadratic_moments.h"

#include <cmath>
#include <cstdlib>

namespace allanlab::estimators {

std::vector<double> DifferenceFilter(Statistic s, std::int64_t m) {
  if (m < 1) return {};
  const auto size = static_cast<std::size_t>(m);
  const double md = static_cast<double>(m);
  std::vector<double> c;
  switch (s) {
    case Statistic::kAllanNonOverlapping:
    case Statistic::kAllanOverlapping:
      c.assign(2 * size, 1.0 / (md * std::sqrt(2.0)));
      for (std::size_t i = 0; i < size; ++i) c[i] = -c[i];
      break;
    case Statistic::kHadamardNonOverlapping:
    case Statistic::kHadamardOverlapping:
      c.assign(3 * size, 1.0 / (md * std::sqrt(6.0)));
      for (std::size_t i = size; i < 2 * size; ++i) c[i] *= -2.0;
      break;
    case Statistic::kModifiedAllan: {
      // Phase x_{k+1} - x_k = tau0 y_k turns sum_j e_j x_{u+j} into tau0 sum_k (sum_{j>k} e_j)
      // y_{u+k}; the tail sums of e = [1, -2, 1] x m run 0 .. -m .. 0 in a triangle-like shape.
      c.assign(3 * size - 1, 0.0);
      double tail = 0.0;
      for (std::int64_t k = 3 * m - 2; k >= 0; --k) {
        const std::int64_t j = k + 1;
        tail += j < m ? 1.0 : (j < 2 * m ? -2.0 : 1.0);
        c[static_cast<std::size_t>(k)] = tail / (md * md * std::sqrt(2.0));
      }
      break;
    }
    case Statistic::kTotal:
    case Statistic::kTime:
      break;
  }
  return c;
}

AvarMoments ExactQuadraticMoments(std::span<const double> autocovariance,
                                  std::span<const double> filter, std::int64_t count,
                                  std::int64_t stride) {
  const auto length = static_cast<std::int64_t>(filter.size());
  if (count < 1 || stride < 1 || length < 1) return {};
  std::vector<long double> acf(static_cast<std::size_t>(length), 0.0L);
  for (std::int64_t j = 0; j < length; ++j) {
    long double sum = 0.0L;
    for (std::int64_t i = 0; i + j < length; ++i) {
      sum += static_cast<long double>(filter[static_cast<std::size_t>(i)]) *
             filter[static_cast<std::size_t>(i + j)];
    }
    acf[static_cast<std::size_t>(j)] = sum;
  }
  auto r = [&](std::int64_t lag) {
    return static_cast<long double>(autocovariance[static_cast<std::size_t>(std::llabs(lag))]);
  };
  auto r_d = [&](std::int64_t l) {
    long double sum = acf[0] * r(l);
    for (std::int64_t j = 1; j < length; ++j) sum += acf[static_cast<std::size_t>(j)] * (r(l + j) + r(l - j));
    return sum;
  };
  const long double c0 = r_d(0);
  long double sum = static_cast<long double>(count) * c0 * c0;
  for (std::int64_t t = 1; t < count; ++t) {
    const long double c = r_d(t * stride);
    sum += 2.0L * static_cast<long double>(count - t) * c * c;
  }
  AvarMoments moments;
  moments.mean = static_cast<double>(c0);
  moments.variance = static_cast<double>(2.0L * sum / (static_cast<long double>(count) * count));
  return moments;
}

}  // namespace allanlab::estimators
