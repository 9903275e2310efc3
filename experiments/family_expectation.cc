#include "experiments/family_expectation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace allanlab::experiments {
namespace {

using estimators::Statistic;

// sum_{i,j} c_i c_j r(|i - j|) for taps c on consecutive samples.
double QuadraticForm(const std::vector<double>& c, const std::vector<double>& r) {
  const std::size_t n = c.size();
  long double sum = 0.0L;
  for (std::size_t k = 0; k < n; ++k) {
    long double lag = 0.0L;
    for (std::size_t i = 0; i + k < n; ++i) lag += static_cast<long double>(c[i]) * c[i + k];
    sum += (k == 0 ? 1.0L : 2.0L) * lag * r[k];
  }
  return static_cast<double>(sum);
}

std::vector<double> Table(const Autocovariance& r, std::size_t length) {
  std::vector<double> t(length);
  for (std::size_t k = 0; k < length; ++k) t[k] = r(static_cast<std::int64_t>(k));
  return t;
}

std::vector<double> AllanTaps(std::int64_t m) {
  std::vector<double> c(static_cast<std::size_t>(2 * m));
  const double w = 1.0 / (static_cast<double>(m) * std::sqrt(2.0));
  for (std::int64_t i = 0; i < 2 * m; ++i) c[static_cast<std::size_t>(i)] = i < m ? -w : w;
  return c;
}

std::vector<double> HadamardTaps(std::int64_t m) {
  std::vector<double> c(static_cast<std::size_t>(3 * m));
  const double w = 1.0 / (static_cast<double>(m) * std::sqrt(6.0));
  for (std::int64_t i = 0; i < 3 * m; ++i) c[static_cast<std::size_t>(i)] = (i / m == 1 ? -2.0 : 1.0) * w;
  return c;
}

std::vector<double> ModifiedTaps(std::int64_t m) {
  const std::vector<double> allan = AllanTaps(m);
  std::vector<double> c(static_cast<std::size_t>(3 * m - 1), 0.0);
  for (std::int64_t shift = 0; shift < m; ++shift) {
    for (std::size_t i = 0; i < allan.size(); ++i) c[i + static_cast<std::size_t>(shift)] += allan[i] / static_cast<double>(m);
  }
  return c;
}

// The total variance: centre i of n - 1 (1 .. n - 1), second difference of the extended phase at
// lag m, as taps on the rate samples (x_a = sum_{k < a} y_k), divided by sqrt(2) m.
double TotalExpectation(std::int64_t m, std::int64_t n, const Autocovariance& r) {
  // Centres m .. n - m are plain Allan differences.
  const std::int64_t inner = std::max<std::int64_t>(0, std::min(n - 1, n - m) - std::max<std::int64_t>(1, m) + 1);
  const std::vector<double> table = Table(r, static_cast<std::size_t>(std::min<std::int64_t>(n, 2 * m + 1)));
  long double sum = static_cast<long double>(inner) * QuadraticForm(AllanTaps(m), table);
  std::vector<double> coefficient(static_cast<std::size_t>(n) + 1);  // of x_0 .. x_n
  for (std::int64_t i = 1; i <= n - 1; ++i) {
    if (i >= m && i <= n - m) continue;
    std::fill(coefficient.begin(), coefficient.end(), 0.0);
    auto add = [&](std::int64_t a, double w) {  // w * x*_a
      if (a < 0) {
        coefficient[0] += 2.0 * w;
        coefficient[static_cast<std::size_t>(-a)] -= w;
      } else if (a > n) {
        coefficient[static_cast<std::size_t>(n)] += 2.0 * w;
        coefficient[static_cast<std::size_t>(2 * n - a)] -= w;
      } else {
        coefficient[static_cast<std::size_t>(a)] += w;
      }
    };
    add(i - m, 1.0);
    add(i, -2.0);
    add(i + m, 1.0);
    // x_a = sum_{k < a} y_k: the tap of y_k is the sum of the coefficients of x_a over a > k.
    std::vector<double> taps(static_cast<std::size_t>(n), 0.0);
    double running = 0.0;
    for (std::int64_t k = n - 1; k >= 0; --k) {
      running += coefficient[static_cast<std::size_t>(k) + 1];
      taps[static_cast<std::size_t>(k)] = running;
    }
    std::size_t lo = 0, hi = taps.size();
    while (lo < hi && taps[lo] == 0.0) ++lo;
    while (hi > lo && taps[hi - 1] == 0.0) --hi;
    std::vector<double> c(taps.begin() + static_cast<std::ptrdiff_t>(lo), taps.begin() + static_cast<std::ptrdiff_t>(hi));
    const double scale = 1.0 / (std::sqrt(2.0) * static_cast<double>(m));
    for (double& v : c) v *= scale;
    sum += QuadraticForm(c, Table(r, c.size()));
  }
  return static_cast<double>(sum / static_cast<long double>(n - 1));
}

}  // namespace

double FamilyExpectation(Statistic statistic, std::int64_t m, std::int64_t n, double tau0_s,
                         const Autocovariance& r) {
  if (m < 1 || n < 2) throw std::invalid_argument("family expectation: m >= 1 and n >= 2 needed");
  switch (statistic) {
    case Statistic::kAllanNonOverlapping:
    case Statistic::kAllanOverlapping:
      if (2 * m > n) throw std::invalid_argument("family expectation: m > n/2");
      return QuadraticForm(AllanTaps(m), Table(r, static_cast<std::size_t>(2 * m)));
    case Statistic::kHadamardNonOverlapping:
    case Statistic::kHadamardOverlapping:
      if (3 * m > n) throw std::invalid_argument("family expectation: m > n/3");
      return QuadraticForm(HadamardTaps(m), Table(r, static_cast<std::size_t>(3 * m)));
    case Statistic::kModifiedAllan:
    case Statistic::kTime: {
      if (3 * m > n) throw std::invalid_argument("family expectation: m > n/3");
      const double mvar = QuadraticForm(ModifiedTaps(m), Table(r, static_cast<std::size_t>(3 * m - 1)));
      if (statistic == Statistic::kModifiedAllan) return mvar;
      const double tau = static_cast<double>(m) * tau0_s;
      return tau * tau * mvar / 3.0;
    }
    case Statistic::kTotal:
      if (m >= n) throw std::invalid_argument("family expectation: m >= n");
      return TotalExpectation(m, n, r);
  }
  throw std::invalid_argument("family expectation: unknown statistic");
}

}  // namespace allanlab::experiments
