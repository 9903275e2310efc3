#include "estimators/fit/avar_covariance.h"

#include <algorithm>
#include <cmath>
#include <numbers>


namespace allanlab::estimators {
namespace {

// Unit-coefficient phase variograms V(k) (k >= 0) in (rad/s)^2 s^0 units of the rate sums Y.
// Q, N and K are closed forms evaluated exactly; flicker is tabulated once (long double).
class Variograms {
 public:
  Variograms(double tau0, std::int64_t max_lag, bool with_flicker) : tau0_(tau0) {
    if (!with_flicker) return;
    flicker_.assign(static_cast<std::size_t>(max_lag + 1), 0.0L);
    // R(j) = -(2/pi) sum_{i=1}^{j} 1/(2i-1); V(k+1) - V(k) = R(0) + 2 sum_{j=1}^{k} R(j).
    long double r = 0.0L, u = 0.0L;
    for (std::int64_t k = 0; k < max_lag; ++k) {
      if (k > 0) {
        r -= (2.0L / std::numbers::pi_v<long double>) / (2.0L * k - 1.0L);
        u += 2.0L * r;
      }
      flicker_[k + 1] = flicker_[k] + u;
    }
  }

  // C(k) = Cov(D^{m1}_s, D^{m2}_{s+k}) for coefficient c with unit value.
  double Cross(Coefficient c, std::int64_t k, std::int64_t m1, std::int64_t m2) const {
    static constexpr int kW[3] = {1, -2, 1};
    long double sum = 0.0L;
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        sum += kW[a] * kW[b] * V(c, std::llabs(k + b * m2 - a * m1));
      }
    }
    return static_cast<double>(-sum / (2.0L * m1 * m2));
  }

 private:
  long double V(Coefficient c, std::int64_t k) const {
    switch (c) {
      case Coefficient::kQ: return k == 0 ? 0.0L : 2.0L / (tau0_ * tau0_);
      case Coefficient::kN: return static_cast<long double>(k) / tau0_;
      case Coefficient::kK: {
        const long double kk = static_cast<long double>(k);
        return -tau0_ * (kk * kk * kk - kk) / 6.0L;
      }
      case Coefficient::kB: return flicker_[static_cast<std::size_t>(k)];
      case Coefficient::kR: return 0.0L;
    }
    return 0.0L;
  }

  long double tau0_;
  std::vector<long double> flicker_;
};

// Number of (s, t) start pairs with t - s = k, s in [0, t1), t in [0, t2).
double PairCount(std::int64_t k, std::int64_t t1, std::int64_t t2) {
  const std::int64_t lo = std::max<std::int64_t>(0, -k);
  const std::int64_t hi = std::min(t1, t2 - k);
  return hi > lo ? static_cast<double>(hi - lo) : 0.0;
}

// Flicker's far tail: C(k) ~ -m1 m2 R''(k), R''(k) = -(1/pi) psi''(k + 1/2) for unit B.
// psi''(x) by its asymptotic series (x >= 8.5 here: truncation error below 4e-10 relative), which
// is 100x cheaper than the general polygamma and sits in the innermost loop.
double FlickerTail(std::int64_t k, std::int64_t m1, std::int64_t m2) {
  const double x = std::abs(static_cast<double>(k)) + 0.5;
  const double r = 1.0 / x, r2 = r * r;
  const double psi2 = -r2 * (1.0 + r * (1.0 + r * (0.5 - r2 * (1.0 / 6.0 - r2 * (1.0 / 6.0 - r2 * 3.0 / 10.0)))));
  return static_cast<double>(m1) * m2 * psi2 / std::numbers::pi;
}

}  // namespace

AvarCovarianceModel::AvarCovarianceModel(const AvarCurve& curve, std::span<const Coefficient> terms)
    : taus_(curve.size()) {
  for (Coefficient c : terms) {
    if (c != Coefficient::kR) terms_.push_back(static_cast<int>(c));
  }
  const std::int64_t n = curve.num_samples;
  const bool with_flicker =
      std::find(terms_.begin(), terms_.end(), static_cast<int>(Coefficient::kB)) != terms_.end();
  const std::int64_t max_m = curve.m.back();
  const Variograms variograms(curve.sample_period_s, n + 4 * max_m + 2, with_flicker);

  const std::size_t p = terms_.size();
  g_.assign(p, std::vector<Eigen::MatrixXd>(p, Eigen::MatrixXd::Zero(taus_, taus_)));
  std::vector<double> c(p);
  for (std::size_t x = 0; x < taus_; ++x) {
    for (std::size_t y = x; y < taus_; ++y) {
      const std::int64_t m1 = curve.m[x], m2 = curve.m[y];
      const std::int64_t t1 = n - 2 * m1 + 1, t2 = n - 2 * m2 + 1;
      // Core: C != 0 for |k| < 2(m1 + m2) for Q, N, K; flicker continues, joined to its tail at
      // 4(m1 + m2). Lags with a pair count run from -(t1 - 1) to t2 - 1.
      const std::int64_t core = std::min<std::int64_t>(4 * (m1 + m2), std::max(t1, t2));
      const std::int64_t stride = std::max<std::int64_t>(1, (m1 + m2) / 64);
      std::vector<std::vector<long double>> acc(p, std::vector<long double>(p, 0.0L));
      for (std::int64_t k = -core; k <= core; k += stride) {
        const double count = PairCount(k, t1, t2) * static_cast<double>(stride);
        if (count == 0.0) continue;
        for (std::size_t i = 0; i < p; ++i) {
          c[i] = variograms.Cross(static_cast<Coefficient>(terms_[i]), k, m1, m2);
        }
        for (std::size_t i = 0; i < p; ++i) {
          for (std::size_t j = i; j < p; ++j) acc[i][j] += count * c[i] * c[j];
        }
      }
      if (with_flicker) {
        // Geometric grid over the tail on both sides, trapezoid in k.
        const std::size_t b = static_cast<std::size_t>(
            std::find(terms_.begin(), terms_.end(), static_cast<int>(Coefficient::kB)) -
            terms_.begin());
        const std::int64_t far = std::max(t1, t2);
        for (int side : {-1, 1}) {
          double k_prev = static_cast<double>(core);
          double f_prev = 0.0;
          bool first = true;
          for (double k = static_cast<double>(core); k < static_cast<double>(far); k *= 1.05) {
            const auto ki = static_cast<std::int64_t>(std::llround(k)) * side;
            const double tail = FlickerTail(ki, m1, m2);
            const double f = PairCount(ki, t1, t2) * tail * tail;
            if (!first) acc[b][b] += 0.5 * (f + f_prev) * (k - k_prev);
            first = false;
            k_prev = k;
            f_prev = f;
          }
        }
      }
      const double norm = 1.0 / (2.0 * static_cast<double>(t1) * static_cast<double>(t2));
      for (std::size_t i = 0; i < p; ++i) {
        for (std::size_t j = i; j < p; ++j) {
          const double v = static_cast<double>(acc[i][j]) * norm;
          g_[i][j](x, y) = g_[i][j](y, x) = v;
        }
      }
    }
  }
}

Eigen::MatrixXd AvarCovarianceModel::Covariance(const std::array<double, 5>& theta) const {
  Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(taus_, taus_);
  const std::size_t p = terms_.size();
  for (std::size_t i = 0; i < p; ++i) {
    for (std::size_t j = i; j < p; ++j) {
      // Cross terms C_i C_j appear twice (i < j) in (sum_i theta_i C_i)^2.
      const double w = theta[terms_[i]] * theta[terms_[j]] * (i == j ? 1.0 : 2.0);
      if (w != 0.0) cov += w * g_[i][j];
    }
  }
  return cov;
}

}  // namespace allanlab::estimators
