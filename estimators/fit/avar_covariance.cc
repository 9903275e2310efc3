#include "estimators/fit/avar_covariance.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "estimators/difference_kernel.h"  // CompensatedSum


namespace allanlab::estimators {
namespace {

constexpr double kW[3] = {1.0, -2.0, 1.0};

// Unit-coefficient phase variograms V(u) (u >= 0) of the rate sums Y, and the cross covariances
// C(k) they give. Q, N and K are closed forms; flicker is tabulated once. All in double: the
// fourth differences below cancel at most ~8 of the 16 digits (flicker at u ~ 1e6), far below
// the 1e-3 this model is held to, and double runs several times faster than long double here.
class Variograms {
 public:
  Variograms(double tau0, std::int64_t max_lag, bool with_flicker) : tau0_(tau0) {
    if (!with_flicker) return;
    flicker_.assign(static_cast<std::size_t>(max_lag + 1), 0.0);
    // Unit B: R(j) = -(2/pi) H(j), H(j) = sum_{i=1}^{j} 1/(2i-1), and summing V(k+1) - V(k) =
    // R(0) + 2 sum_{j=1}^{k} R(j) twice in closed form gives
    //   V(u) = -(4/pi) [(u^2 - 1/4) H(u-1) / 2 - (u^2 - 1)/8 - u(u-1)/4],
    // so one compensated running sum (H) makes the table instead of three nested ones.
    CompensatedSum h;
    for (std::int64_t k = 1; k <= max_lag; ++k) {
      if (k >= 2) h.Add(1.0 / (2.0 * static_cast<double>(k) - 3.0));
      const auto u = static_cast<double>(k);
      flicker_[static_cast<std::size_t>(k)] =
          -(4.0 / std::numbers::pi) *
          (0.5 * (u * u - 0.25) * h.Value() - 0.125 * (u * u - 1.0) - 0.25 * u * (u - 1.0));
    }
  }

  // C_c(k) = Cov(D^{m1}_s, D^{m2}_{s+k}) for every coefficient c with unit value, into out[c].
  // The nine lags k + b m2 - a m1 with weights w_a w_b (w = 1, -2, 1) come from the caller.
  void Cross(const std::int64_t* offsets, const double* weights, std::int64_t k, double scale,
             std::array<double, 5>* out) const {
    double q = 0.0, n = 0.0, kk = 0.0, b = 0.0;
    for (int i = 0; i < 9; ++i) {
      const std::int64_t lag = std::llabs(k + offsets[i]);
      const auto u = static_cast<double>(lag);
      const double w = weights[i];
      q += lag == 0 ? 0.0 : w;
      n += w * u;
      kk += w * (u * u * u - u);
      if (!flicker_.empty()) b += w * flicker_[static_cast<std::size_t>(lag)];
    }
    (*out)[static_cast<int>(Coefficient::kQ)] = scale * q * 2.0 / (tau0_ * tau0_);
    (*out)[static_cast<int>(Coefficient::kN)] = scale * n / tau0_;
    (*out)[static_cast<int>(Coefficient::kK)] = scale * -tau0_ * kk / 6.0;
    (*out)[static_cast<int>(Coefficient::kB)] = scale * b;
    (*out)[static_cast<int>(Coefficient::kR)] = 0.0;
  }

 private:
  double tau0_;
  std::vector<double> flicker_;
};

// The lags k the core sum of the pair (m1, m2) visits, for a record of n samples.
struct PairRange {
  PairRange(std::int64_t n, std::int64_t m1, std::int64_t m2)
      : t1(n - 2 * m1 + 1),
        t2(n - 2 * m2 + 1),
        // Core: C != 0 for |k| < 2(m1 + m2) for Q, N, K; flicker continues, joined to its tail
        // at 4(m1 + m2).
        core(std::min<std::int64_t>(4 * (m1 + m2), std::max(t1, t2))),
        // Lags with pairs: -(t1 - 1) .. t2 - 1. The strided grid is centred on k = 0 and has at
        // least ~128 points over that range: a grid started at -core skipped k = 0 when the
        // range was shorter than the stride (m = N/2: a zero variance and a covariance that was
        // not positive definite, so GLS failed on plain white noise).
        k_lo(std::max(-core, -(t1 - 1))),
        k_hi(std::min(core, t2 - 1)) {}
  std::int64_t t1, t2;  // Allan differences (start counts) of m1 and m2
  std::int64_t core;
  std::int64_t k_lo, k_hi;
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
  // The largest lag any pair reads: |k + b m2 - a m1| for k in [k_lo, k_hi] (the quantization
  // spikes lie there too), so at most max(|k_lo - 2 m1|, |k_hi + 2 m2|). The table is
  // record-sized: building only what is read saves time and memory (at 1e7 samples on the
  // dense:10 grid, 1.0e7 entries instead of the 1.8e7 of the bound core + 2 max(m1, m2)).
  std::int64_t max_lag = 0;
  for (std::size_t x = 0; x < taus_; ++x) {
    for (std::size_t y = x; y < taus_; ++y) {
      const PairRange r(n, curve.m[x], curve.m[y]);
      max_lag = std::max<std::int64_t>(
          {max_lag, std::llabs(r.k_lo - 2 * curve.m[x]), std::llabs(r.k_hi + 2 * curve.m[y])});
    }
  }
  const Variograms variograms(curve.sample_clock.period_s(), max_lag + 2, with_flicker);

  const std::size_t p = terms_.size();
  const auto q_position = static_cast<std::size_t>(
      std::find(terms_.begin(), terms_.end(), static_cast<int>(Coefficient::kQ)) - terms_.begin());
  g_.assign(p, std::vector<Eigen::MatrixXd>(p, Eigen::MatrixXd::Zero(taus_, taus_)));
  std::vector<double> c(p);
  for (std::size_t x = 0; x < taus_; ++x) {
    for (std::size_t y = x; y < taus_; ++y) {
      const std::int64_t m1 = curve.m[x], m2 = curve.m[y];
      const PairRange range(n, m1, m2);
      const std::int64_t t1 = range.t1, t2 = range.t2, core = range.core;
      const std::int64_t k_lo = range.k_lo, k_hi = range.k_hi;
      const std::int64_t stride =
          std::max<std::int64_t>(1, std::min<std::int64_t>((m1 + m2) / 64, (k_hi - k_lo) / 128));
      std::vector<std::vector<double>> acc(p, std::vector<double>(p, 0.0));
      std::int64_t offsets[9];
      double weights[9];
      for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) {
          offsets[3 * a + b] = b * m2 - a * m1;
          weights[3 * a + b] = kW[a] * kW[b];
        }
      }
      const double scale = -1.0 / (2.0 * static_cast<double>(m1) * static_cast<double>(m2));
      std::array<double, 5> all{};
      // Quantization (white angle) has V(u) = const for u > 0, so C_Q(k) vanishes except at the
      // isolated lags k = a m1 - b m2 where one of the nine lags is zero: a strided grid misses
      // those spikes or weights them by the stride (Q + N fits had N's sigma 4x too small). With
      // a stride, every product with C_Q is summed exactly over the spikes instead.
      const bool q_spikes = stride > 1 && q_position < p;
      for (std::int64_t k = k_lo + (-k_lo) % stride; k <= k_hi; k += stride) {
        const double count = PairCount(k, t1, t2) * static_cast<double>(stride);
        if (count == 0.0) continue;
        variograms.Cross(offsets, weights, k, scale, &all);
        for (std::size_t i = 0; i < p; ++i) c[i] = all[static_cast<std::size_t>(terms_[i])];
        if (q_spikes) c[q_position] = 0.0;
        for (std::size_t i = 0; i < p; ++i) {
          const double ci = count * c[i];
          for (std::size_t j = i; j < p; ++j) acc[i][j] += ci * c[j];
        }
      }
      if (q_spikes) {
        std::vector<std::int64_t> spikes(offsets, offsets + 9);
        for (std::int64_t& k : spikes) k = -k;
        std::sort(spikes.begin(), spikes.end());
        spikes.erase(std::unique(spikes.begin(), spikes.end()), spikes.end());
        for (std::int64_t k : spikes) {
          const double count = PairCount(k, t1, t2);
          if (count == 0.0) continue;
          variograms.Cross(offsets, weights, k, scale, &all);
          for (std::size_t i = 0; i < p; ++i) c[i] = all[static_cast<std::size_t>(terms_[i])];
          for (std::size_t i = 0; i < p; ++i) {
            for (std::size_t j = i; j < p; ++j) {
              if (i == q_position || j == q_position) acc[i][j] += count * c[i] * c[j];
            }
          }
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
