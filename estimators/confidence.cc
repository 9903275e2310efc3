#include "estimators/confidence.h"

#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <cmath>
#include <limits>

namespace allanlab::estimators {
namespace {

// Greenhall & Riley (2003) work with the continuous-time phase: w is a pure power-law process,
// x its tau0-average (filter factor F) and z the d-th difference at lag m. Times are in units
// of tau = m tau0, which makes every quantity below independent of m except through F.
constexpr double kInfinite = std::numeric_limits<double>::infinity();
constexpr int kJMax = 100;  // the paper's suggested cut-off for the exact sum

// Generalised autocovariance of w for S_y ~ f^alpha, up to a factor that cancels in the EDF
// (paper eq. 7). The log terms vanish at t = 0 by continuity.
double Sw(double t, int alpha) {
  const double a = std::abs(t);
  const double log_a = a > 0.0 ? std::log(a) : 0.0;
  switch (alpha) {
    case 2:
      return -a;
    case 1:
      return a * a * log_a;
    case 0:
      return a * a * a;
    case -1:
      return std::pow(a, 4) * log_a;
    case -2:
      return std::pow(a, 5);
    case -3:
      return std::pow(a, 6) * log_a;
    default:  // -4
      return std::pow(a, 7);
  }
}

// Eq. 8: the phase averaged over 1/F of a tau; F = infinity is the limit of no averaging, where
// the second difference of Sw becomes Sw of the next exponent.
double Sx(double t, double f, int alpha) {
  if (std::isinf(f)) return Sw(t, alpha + 2);
  return f * f * (2.0 * Sw(t, alpha) - Sw(t - 1.0 / f, alpha) - Sw(t + 1.0 / f, alpha));
}

// Eq. 9: d-th central difference (binomial weights with alternating signs).
double Sz(double t, double f, int alpha, int d) {
  static constexpr double kWeights[4][4] = {
      {1, 0, 0, 0}, {2, -1, 0, 0}, {6, -4, 1, 0}, {20, -15, 6, -1}};
  double sum = kWeights[d][0] * Sx(t, f, alpha);
  for (int k = 1; k <= d; ++k) {
    sum += kWeights[d][k] * (Sx(t - k, f, alpha) + Sx(t + k, f, alpha));
  }
  return sum;
}

// Eq. 10. J, M and S are real here: the fallback branches pass a fractional stride m'.
double BasicSum(double j_terms, double big_m, double s, double f, int alpha, int d) {
  const double z0 = Sz(0.0, f, alpha, d);
  const double zj = Sz(j_terms / s, f, alpha, d);
  double sum = z0 * z0 + (1.0 - j_terms / big_m) * zj * zj;
  for (int j = 1; j < static_cast<int>(j_terms); ++j) {
    const double z = Sz(j / s, f, alpha, d);
    sum += 2.0 * (1.0 - j / big_m) * z * z;
  }
  return sum;
}

struct Coefficients {
  double c0 = 0.0, c1 = 0.0;
};

// Tables 1 (modified) and 2 (unmodified): large-r expansion 1/edf = (c0 - c1/r)/r, rows
// alpha = 2..-4, columns d = 1..3. Cells the domain alpha + 2d > 1 excludes are zero.
Coefficients LargeRatioCoefficients(bool modified, int alpha, int d) {
  static constexpr Coefficients kTable1[7][3] = {
      {{2.0 / 3.0, 1.0 / 3.0}, {7.0 / 9.0, 1.0 / 2.0}, {22.0 / 25.0, 2.0 / 3.0}},
      {{0.840, 0.345}, {0.997, 0.616}, {1.141, 0.843}},
      {{1.079, 0.368}, {1.033, 0.607}, {1.184, 0.848}},
      {{}, {1.048, 0.534}, {1.180, 0.816}},
      {{}, {1.302, 0.535}, {1.175, 0.777}},
      {{}, {}, {1.194, 0.703}},
      {{}, {}, {1.489, 0.702}}};
  static constexpr Coefficients kTable2[7][3] = {
      {{3.0 / 2.0, 1.0 / 2.0}, {35.0 / 18.0, 1.0}, {231.0 / 100.0, 3.0 / 2.0}},
      {{78.6, 25.2}, {790.0, 410.0}, {9950.0, 6520.0}},
      {{2.0 / 3.0, 1.0 / 6.0}, {2.0 / 3.0, 1.0 / 3.0}, {7.0 / 9.0, 1.0 / 2.0}},
      {{}, {0.852, 0.375}, {0.997, 0.617}},
      {{}, {1.079, 0.368}, {1.033, 0.607}},
      {{}, {}, {1.053, 0.553}},
      {{}, {}, {1.302, 0.535}}};
  return modified ? kTable1[2 - alpha][d - 1] : kTable2[2 - alpha][d - 1];
}

// Table 3 (alpha = 1, unmodified): sz(0, m) ~ b0 + b1 ln m.
Coefficients FlickerPhaseNormaliser(int d) {
  static constexpr Coefficients kTable3[3] = {{6.0, 4.0}, {15.23, 12.0}, {47.8, 40.0}};
  return kTable3[d - 1];
}

double Binomial(int n, int k) {
  double b = 1.0;
  for (int i = 1; i <= k; ++i) b = b * (n - k + i) / i;
  return b;
}

// Case 4 (unmodified, white phase): the d-th differences of white phase at lag m correlate only
// at lags k m, k <= d, with rho_k = C(2d, d-k)/C(2d, d) up to sign, so the variance is a finite
// sum. For K = ceil(r) > d this is the paper's (a0 - a1/r)/M with a0 = C(4d,2d)/C(2d,d)^2 and
// a1 = d/2; for K <= d (the case allantools leaves out) the same sum just stops at K - 1.
double WhitePhaseInverseEdf(int d, double big_m, double r) {
  const int k_max = std::min(d, static_cast<int>(std::ceil(r)) - 1);
  const double centre = Binomial(2 * d, d);
  double sum = 1.0;
  for (int k = 1; k <= k_max; ++k) {
    const double rho = Binomial(2 * d, d - k) / centre;
    sum += 2.0 * (1.0 - k / r) * rho * rho;
  }
  return sum / big_m;
}

// NIST SP 1065 Table 5 ("simple" EDF approximations, N phase points) for the phase noises, which
// Table 7 leaves out; Stable32 uses them for TOTDEV there (its OCXO reference intervals at
// alpha = 1 reproduce them) and so does allantools.
double SimplePhaseNoiseEdf(int alpha, std::int64_t m, std::int64_t n_phase) {
  const double n = static_cast<double>(n_phase);
  const double md = static_cast<double>(m);
  if (alpha == 2) return (n + 1.0) * (n - 2.0 * md) / (2.0 * (n - md));
  const double a = (n - 1.0) / (2.0 * md);
  const double b = (2.0 * md + 1.0) * (n - 1.0) / 4.0;
  if (a <= 1.0) return 0.0;
  return std::exp(std::sqrt(std::log(a) * std::log(b)));
}

}  // namespace

double GreenhallRileyEdf(int alpha, int d, std::int64_t m, std::int64_t n_phase, bool overlapping,
                         bool modified) {
  if (d < 1 || d > 3 || alpha < -4 || alpha > 2 || alpha + 2 * d <= 1 || m < 1) return 0.0;
  const double md = static_cast<double>(m);
  const double f = modified ? 1.0 : md;
  const double s = overlapping ? md : 1.0;
  const double filter_length = md / f + md * d;  // L, in phase samples
  const double n = static_cast<double>(n_phase);
  if (n < filter_length) return 0.0;
  const double big_m = 1.0 + std::floor(s * (n - filter_length) / md);  // terms averaged
  const double j_terms = std::min(big_m, (d + 1) * s);
  const double r = big_m / s;
  const bool large_r = r > d + 1;

  double inverse = 0.0;
  if (modified) {
    if (j_terms <= kJMax) {
      const double z0 = Sz(0.0, 1.0, alpha, d);
      inverse = BasicSum(j_terms, big_m, s, 1.0, alpha, d) / (big_m * z0 * z0);
    } else if (large_r) {
      const Coefficients c = LargeRatioCoefficients(true, alpha, d);
      inverse = (c.c0 - c.c1 / r) / r;
    } else {
      const double z0 = Sz(0.0, 1.0, alpha, d);
      inverse = BasicSum(kJMax, kJMax, kJMax / r, 1.0, alpha, d) / (kJMax * z0 * z0);
    }
  } else if (alpha <= 0) {
    if (j_terms <= kJMax) {
      // Beyond J_max / (d + 1) the tau0 averaging no longer matters; F = infinity avoids the
      // cancellation of nearly equal Sw values at large F.
      const double f_used = md * (d + 1) <= kJMax ? md : kInfinite;
      const double z0 = Sz(0.0, f_used, alpha, d);
      inverse = BasicSum(j_terms, big_m, s, f_used, alpha, d) / (big_m * z0 * z0);
    } else if (large_r) {
      const Coefficients c = LargeRatioCoefficients(false, alpha, d);
      inverse = (c.c0 - c.c1 / r) / r;
    } else {
      const double z0 = Sz(0.0, kInfinite, alpha, d);
      inverse = BasicSum(kJMax, kJMax, kJMax / r, kInfinite, alpha, d) / (kJMax * z0 * z0);
    }
  } else if (alpha == 1) {
    // Flicker phase: sz(0, m) grows like ln m, so the large-r branches need Table 3.
    const Coefficients b = FlickerPhaseNormaliser(d);
    const double norm = b.c0 + b.c1 * std::log(md);
    if (j_terms <= kJMax) {
      const double z0 = Sz(0.0, md, alpha, d);
      inverse = BasicSum(j_terms, big_m, s, md, alpha, d) / (big_m * z0 * z0);
    } else if (large_r) {
      const Coefficients c = LargeRatioCoefficients(false, alpha, d);
      inverse = (c.c0 - c.c1 / r) / (r * norm * norm);
    } else {
      const double m_prime = kJMax / r;
      inverse = BasicSum(kJMax, kJMax, m_prime, m_prime, alpha, d) / (kJMax * norm * norm);
    }
  } else {
    inverse = WhitePhaseInverseEdf(d, big_m, r);
  }
  return inverse > 0.0 ? 1.0 / inverse : 0.0;
}

double TotalVarianceEdf(int alpha, double record_length_s, double tau_s) {
  static constexpr Coefficients kTable7[3] = {{1.50, 0.0}, {1.17, 0.22}, {0.93, 0.36}};
  if (alpha > 0 || alpha < -2 || !(tau_s > 0.0) || !(record_length_s > 0.0)) return 0.0;
  const Coefficients c = kTable7[-alpha];
  return std::max(0.0, c.c0 * record_length_s / tau_s - c.c1);
}

double StatisticEdf(Statistic s, int alpha, std::int64_t m, std::int64_t n_rate, double tau0_s) {
  const std::int64_t n_phase = n_rate + 1;
  if (s == Statistic::kTotal) {
    // SP 1065 and allantools measure T in phase points: T = n_phase tau0.
    if (alpha <= 0) return TotalVarianceEdf(alpha, n_phase * tau0_s, m * tau0_s);
    return std::max(0.0, SimplePhaseNoiseEdf(alpha, m, n_phase));
  }
  return GreenhallRileyEdf(alpha, DifferenceOrder(s), m, n_phase, IsOverlapping(s), IsModified(s));
}

double BoundTotalVarianceEdf(double total_edf, double oavar_edf, std::int64_t m, std::int64_t n_rate) {
  if (m < 1 || 2 * m > n_rate || !(oavar_edf > 0.0)) return total_edf;
  const double terms = static_cast<double>(n_rate - 1) / static_cast<double>(n_rate - 2 * m + 1);
  return std::min(total_edf, oavar_edf * terms);
}

double SimpleEdf(std::int64_t clusters) {
  return clusters >= 2 ? static_cast<double>(clusters - 1) : 0.0;
}

Interval ChiSquareInterval(double variance, double edf, double confidence) {
  if (!(edf > 0.0) || !std::isfinite(edf) || !(confidence > 0.0) || !(confidence < 1.0)) {
    return {0.0, std::numeric_limits<double>::infinity()};
  }
  const boost::math::chi_squared chi2(edf);
  const double p = 0.5 * (1.0 - confidence);
  return {variance * edf / boost::math::quantile(chi2, 1.0 - p),
          variance * edf / boost::math::quantile(chi2, p)};
}

}  // namespace allanlab::estimators
