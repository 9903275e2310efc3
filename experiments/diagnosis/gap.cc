#include "experiments/diagnosis/gap.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/fisher_f.hpp>
#include <boost/math/special_functions/digamma.hpp>
#include <boost/math/special_functions/trigamma.hpp>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>

namespace allanlab::experiments {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kMaxZ = 37.0;  // Phi^{-1} of the smallest normal double tail

// z from the lower tail p and the upper tail q = 1 - p (each computed directly, so far tails
// keep their digits).
double ZFromTails(double p, double q) {
  const boost::math::normal normal;
  if (p < q) return p > 0.0 ? std::max(-kMaxZ, boost::math::quantile(normal, p)) : -kMaxZ;
  return q > 0.0 ? std::min(kMaxZ, -boost::math::quantile(normal, q)) : kMaxZ;
}

}  // namespace

double ZFromChiSquare(double observed, double expected, double edf) {
  if (!(observed > 0.0) || !(expected > 0.0) || !(edf > 0.0) || !std::isfinite(observed)) return kNaN;
  const boost::math::chi_squared chi2(edf);
  const double x = edf * observed / expected;
  return ZFromTails(boost::math::cdf(chi2, x), boost::math::cdf(boost::math::complement(chi2, x)));
}

double ZFromEnvelope(double observed, double mean, double sd, int trials) {
  if (!std::isfinite(observed) || !std::isfinite(mean) || !(sd > 0.0) || trials < 3) return kNaN;
  const double t = (observed - mean) / (sd * std::sqrt(1.0 + 1.0 / trials));
  const boost::math::students_t dist(trials - 1);
  return ZFromTails(boost::math::cdf(dist, t), boost::math::cdf(boost::math::complement(dist, t)));
}

namespace {

// The degrees of freedom nu at which `log_variance(nu)` (decreasing in nu) equals s^2, bisected
// in ln nu over [0.05, 1e7]: 0.05 when even that is narrower; NaN when even 1e7 is wider than s
// (a spread no such law gives: the caller falls back to the Student reading).
template <class LogVariance>
double MatchDegreesOfFreedom(double s, const LogVariance& log_variance) {
  double lo = std::log(0.05), hi = std::log(1e7);
  if (log_variance(std::exp(hi)) >= s * s) return kNaN;
  if (log_variance(std::exp(lo)) <= s * s) return std::exp(lo);
  for (int it = 0; it < 60 && hi - lo > 1e-6; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (log_variance(std::exp(mid)) > s * s) lo = mid; else hi = mid;
  }
  return std::exp(0.5 * (lo + hi));
}

// The Student reading carries the uncertainty of an sd from few trials, the law's reading the
// statistic's own tails: the smaller |z| of the two honours both, near any threshold. Far beyond
// every threshold both say the point departs, and there the Student reading only compresses the
// departure (t = 40 on 29 degrees of freedom reads z = 10.6): a model whose views came from an
// envelope then out-scored one whose views came from theory on a record far from both (on the
// ADIS16405 Gyro_Z record, a telegraph of 0.003 deg/h beside the resonance "explained" half the
// held-out chi2). So from |z_student| = 4 to 6 the reading passes linearly to the law's.
constexpr double kStudentReadingFrom = 4.0, kStudentReadingTo = 6.0;
double SmallerInMagnitude(double z_law, double z_student) {
  const double smaller = std::abs(z_law) < std::abs(z_student) ? z_law : z_student;
  const double w = std::clamp((std::abs(z_student) - kStudentReadingFrom) / (kStudentReadingTo - kStudentReadingFrom), 0.0, 1.0);
  return w == 0.0 ? smaller : smaller + w * (z_law - smaller);
}

}  // namespace

double ZFromLogRatio(double observed, double edf) { return ZFromLogRatio(observed, edf, edf); }

double ZFromLogRatio(double observed, double edf_first, double edf_second) {
  if (!std::isfinite(observed) || !(edf_first > 0.0) || !(edf_second > 0.0)) return kNaN;
  const boost::math::fisher_f f(edf_first, edf_second);
  const double x = std::exp(observed);
  return ZFromTails(boost::math::cdf(f, x), boost::math::cdf(boost::math::complement(f, x)));
}

double ZFromLogRatioEnvelope(double observed, double mean, double sd, int trials) {
  if (!std::isfinite(observed) || !std::isfinite(mean) || !(sd > 0.0) || trials < 3) return kNaN;
  const double s = sd * std::sqrt(1.0 + 1.0 / trials);
  // Var ln F(nu, nu) = 2 psi'(nu / 2).
  const double nu = MatchDegreesOfFreedom(s, [](double n) { return 2.0 * boost::math::trigamma(0.5 * n); });
  const double z_t = ZFromEnvelope(observed, mean, sd, trials);
  if (!std::isfinite(nu)) return z_t;
  return SmallerInMagnitude(ZFromLogRatio(observed - mean, nu), z_t);
}

double ZFromLogRange(double observed, double edf, int count) {
  if (!std::isfinite(observed) || !(observed >= 0.0) || !(edf > 0.0) || count < 2) return kNaN;
  // Y = ln(chi2_nu / nu), G its distribution function, g its density. The range R of `count`
  // independent Y has P(R <= r) = count int g(y) (G(y + r) - G(y))^(count - 1) dy, and
  // P(R > r) = count int g(y) ((1 - G(y))^(count - 1) - (G(y + r) - G(y))^(count - 1)) dy, the
  // difference a^(n-1) - b^(n-1) = (a - b) sum a^j b^(n-2-j) taken with a - b = 1 - G(y + r)
  // from the complement, so the far upper tail keeps its digits. Simpson's rule in y between
  // the 1e-15 quantiles of Y.
  const boost::math::chi_squared chi2(edf);
  const double y_lo = std::log(boost::math::quantile(chi2, 1e-15) / edf);
  const double y_hi = std::log(boost::math::quantile(boost::math::complement(chi2, 1e-15)) / edf);
  constexpr int kIntervals = 800;  // even
  const double h = (y_hi - y_lo) / kIntervals;
  double below = 0.0, above = 0.0;
  for (int i = 0; i <= kIntervals; ++i) {
    const double y = y_lo + h * i;
    const double x = edf * std::exp(y);
    const double density = boost::math::pdf(chi2, x) * x;
    const double upper_y = boost::math::cdf(boost::math::complement(chi2, x));  // 1 - G(y)
    const double x_r = edf * std::exp(y + observed);
    const double upper_yr = boost::math::cdf(boost::math::complement(chi2, x_r));  // 1 - G(y + r)
    const double a = upper_y, b = std::max(0.0, upper_y - upper_yr);
    double powers = 0.0;  // sum_{j=0}^{count-2} a^j b^(count-2-j)
    for (int j = 0; j <= count - 2; ++j) powers += std::pow(a, j) * std::pow(b, count - 2 - j);
    const double weight = (i == 0 || i == kIntervals) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
    below += weight * density * std::pow(b, count - 1);
    above += weight * density * upper_yr * powers;
  }
  below *= count * h / 3.0;
  above *= count * h / 3.0;
  return ZFromTails(below, above);
}

double ZFromLogRangeOfUnequal(double observed, std::span<const double> log_means, std::span<const double> edfs) {
  const std::size_t count = log_means.size();
  if (!std::isfinite(observed) || !(observed >= 0.0) || count < 2 || edfs.size() != count) return kNaN;
  // The distinct laws and how many windows share each (the windows a drift has left are alike).
  // In double: boost's default promotion to long double made each law evaluation several times
  // slower, and 1e-15 tails need no more.
  using Fast = boost::math::policies::policy<boost::math::policies::promote_double<false>>;
  struct Law {
    double log_mean, edf;
    int windows;
    boost::math::chi_squared_distribution<double, Fast> chi2;
  };
  std::vector<Law> laws;
  for (std::size_t w = 0; w < count; ++w) {
    if (!std::isfinite(log_means[w]) || !(edfs[w] > 0.0)) return kNaN;
    auto same = std::find_if(laws.begin(), laws.end(),
                             [&](const Law& l) { return l.log_mean == log_means[w] && l.edf == edfs[w]; });
    if (same != laws.end()) {
      ++same->windows;
    } else {
      laws.push_back({log_means[w], edfs[w], 1, boost::math::chi_squared_distribution<double, Fast>(edfs[w])});
    }
  }
  // Y_w = ln E_w + ln(chi2_w / nu_w), G_w its distribution function, g_w its density. With Y_j the
  // minimum, P(R <= r) = sum_j int g_j(y) prod_{k != j} (G_k(y + r) - G_k(y)) dy and
  // P(R > r) = sum_j int g_j(y) (prod_{k != j} a_k - prod_{k != j} b_k) dy, a_k = 1 - G_k(y),
  // b_k = a_k - u_k, u_k = 1 - G_k(y + r); the difference of the products is
  // sum_k u_k prod_{l < k} b_l prod_{l > k} a_l (over l != j), so the far upper tail keeps its
  // digits, as in ZFromLogRange. Each j's integral by Simpson's rule over its own law's 1e-15
  // quantile range (the laws' widths differ: one grid over their union could miss a narrow one).
  constexpr int kIntervals = 800;  // even
  const std::size_t groups = laws.size();
  std::vector<double> a(groups), b(groups), u(groups);
  std::vector<std::size_t> others;  // the law of each window but the minimum's
  double below = 0.0, above = 0.0;
  for (std::size_t j = 0; j < groups; ++j) {
    const Law& min_law = laws[j];
    others.clear();
    for (std::size_t g = 0; g < groups; ++g) {
      for (int w = 0; w < laws[g].windows - (g == j ? 1 : 0); ++w) others.push_back(g);
    }
    const double y_lo = min_law.log_mean + std::log(boost::math::quantile(min_law.chi2, 1e-15) / min_law.edf);
    const double y_hi =
        min_law.log_mean + std::log(boost::math::quantile(boost::math::complement(min_law.chi2, 1e-15)) / min_law.edf);
    const double h = (y_hi - y_lo) / kIntervals;
    double in_j = 0.0, out_j = 0.0;
    for (int i = 0; i <= kIntervals; ++i) {
      const double y = y_lo + h * i;
      const double x = min_law.edf * std::exp(y - min_law.log_mean);
      const double density = boost::math::pdf(min_law.chi2, x) * x;
      if (!(density > 0.0)) continue;
      for (std::size_t g = 0; g < groups; ++g) {
        const Law& l = laws[g];
        a[g] = boost::math::cdf(boost::math::complement(l.chi2, l.edf * std::exp(y - l.log_mean)));
        u[g] = boost::math::cdf(boost::math::complement(l.chi2, l.edf * std::exp(y + observed - l.log_mean)));
        b[g] = std::max(0.0, a[g] - u[g]);
      }
      double product_b = 1.0, difference = 0.0;
      for (std::size_t k = 0; k < others.size(); ++k) {
        product_b *= b[others[k]];
        double term = u[others[k]];
        for (std::size_t l = 0; l < others.size(); ++l) {
          if (l != k) term *= l < k ? b[others[l]] : a[others[l]];
        }
        difference += term;
      }
      const double weight = (i == 0 || i == kIntervals) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
      in_j += weight * density * product_b;
      out_j += weight * density * difference;
    }
    below += min_law.windows * in_j * h / 3.0;
    above += min_law.windows * out_j * h / 3.0;
  }
  return ZFromTails(below, above);
}

double ZFromLogVarianceEnvelope(double observed, double mean, double sd, int trials) {
  if (!std::isfinite(observed) || !std::isfinite(mean) || !(sd > 0.0) || trials < 3) return kNaN;
  const double s = sd * std::sqrt(1.0 + 1.0 / trials);
  // ln(chi2_nu / nu): variance psi'(nu / 2), mean psi(nu / 2) - ln(nu / 2).
  const double nu = MatchDegreesOfFreedom(s, [](double n) { return boost::math::trigamma(0.5 * n); });
  const double z_t = ZFromEnvelope(observed, mean, sd, trials);
  if (!std::isfinite(nu)) return z_t;
  const double log_mean = boost::math::digamma(0.5 * nu) - std::log(0.5 * nu);
  const double x = nu * std::exp(observed - mean + log_mean);  // ~ chi2_nu under the model
  const boost::math::chi_squared chi2(nu);
  return SmallerInMagnitude(ZFromTails(boost::math::cdf(chi2, x), boost::math::cdf(boost::math::complement(chi2, x))), z_t);
}

namespace {

// Anscombe & Glynn (1983): the kurtosis b2 of n independent normal values mapped to an
// approximately standard normal z, by the moments of b2 and a Wilson-Hilferty cube.
double AnscombeGlynnZ(double b2, double n) {
  const double mean = 3.0 * (n - 1.0) / (n + 1.0);
  const double variance = 24.0 * n * (n - 2.0) * (n - 3.0) / ((n + 1.0) * (n + 1.0) * (n + 3.0) * (n + 5.0));
  const double x = (b2 - mean) / std::sqrt(variance);
  const double skew = 6.0 * (n * n - 5.0 * n + 2.0) / ((n + 7.0) * (n + 9.0)) *
                      std::sqrt(6.0 * (n + 3.0) * (n + 5.0) / (n * (n - 2.0) * (n - 3.0)));
  const double a = 6.0 + 8.0 / skew * (2.0 / skew + std::sqrt(1.0 + 4.0 / (skew * skew)));
  const double denominator = 1.0 + x * std::sqrt(2.0 / (a - 4.0));
  if (!(denominator > 0.0)) return -kMaxZ;  // below the law's lower end
  const double z = ((1.0 - 2.0 / (9.0 * a)) - std::cbrt((1.0 - 2.0 / a) / denominator)) / std::sqrt(2.0 / (9.0 * a));
  return std::clamp(z, -kMaxZ, kMaxZ);
}

double AnscombeGlynnVariance(double n) {
  return 24.0 * n * (n - 2.0) * (n - 3.0) / ((n + 1.0) * (n + 1.0) * (n + 3.0) * (n + 5.0));
}

}  // namespace

double ZFromKurtosis(double excess_kurtosis, double effective_count) {
  if (!std::isfinite(excess_kurtosis) || !(effective_count > 8.0)) return kNaN;
  return AnscombeGlynnZ(excess_kurtosis + 3.0, effective_count);
}

double ZFromKurtosisEnvelope(double observed, double mean, double sd, int trials) {
  if (!std::isfinite(observed) || !std::isfinite(mean) || !(sd > 0.0) || trials < 3) return kNaN;
  const double s = sd * std::sqrt(1.0 + 1.0 / trials);
  const double z_t = ZFromEnvelope(observed, mean, sd, trials);
  // The effective n whose b2 variance matches the envelope's, bisected in ln n over [8, 1e12]
  // (the variance falls with n there).
  double lo = std::log(8.0), hi = std::log(1e12);
  if (AnscombeGlynnVariance(std::exp(lo)) <= s * s || AnscombeGlynnVariance(std::exp(hi)) >= s * s) return z_t;
  for (int it = 0; it < 80 && hi - lo > 1e-9; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (AnscombeGlynnVariance(std::exp(mid)) > s * s) lo = mid; else hi = mid;
  }
  const double n = std::exp(0.5 * (lo + hi));
  const double b2 = observed - mean + 3.0 * (n - 1.0) / (n + 1.0);
  return SmallerInMagnitude(AnscombeGlynnZ(b2, n), z_t);
}

double BonferroniThreshold(double alpha, int points) {
  const boost::math::normal normal;
  return -boost::math::quantile(normal, alpha / (2.0 * std::max(points, 1)));
}

Band ChiSquareBand(double expected, double edf, double probability) {
  const boost::math::chi_squared chi2(edf);
  const double tail = 0.5 * (1.0 - probability);
  return {expected * boost::math::quantile(chi2, tail) / edf,
          expected * boost::math::quantile(boost::math::complement(chi2, tail)) / edf};
}

GapMetrics Metrics(const std::vector<double>& z) {
  GapMetrics m;
  int inside = 0;
  for (double v : z) {
    if (!std::isfinite(v)) continue;
    ++m.points;
    m.chi2 += v * v;
    if (std::abs(v) <= 1.959964) ++inside;
    m.max_abs_z = std::max(m.max_abs_z, std::abs(v));
  }
  m.fraction_in_95 = m.points > 0 ? static_cast<double>(inside) / m.points : 1.0;
  return m;
}

GapMetrics Metrics(const std::vector<ViewResiduals>& views) {
  std::vector<double> all;
  for (const ViewResiduals& v : views) all.insert(all.end(), v.z.begin(), v.z.end());
  return Metrics(all);
}

std::vector<GapRegion> FindGapRegions(const std::vector<ViewResiduals>& views, double threshold) {
  std::vector<GapRegion> regions;
  for (const ViewResiduals& v : views) {
    std::size_t i = 0;
    while (i < v.z.size()) {
      if (!(std::abs(v.z[i]) > threshold)) {
        ++i;
        continue;
      }
      GapRegion r;
      r.view = v.view;
      r.x_min = v.x[i];
      double sum = 0.0;
      int count = 0;
      // A region runs while |z| stays above threshold (NaN points do not break it).
      while (i < v.z.size() && (std::abs(v.z[i]) > threshold || !std::isfinite(v.z[i]))) {
        if (std::isfinite(v.z[i])) {
          r.x_max = v.x[i];
          if (std::abs(v.z[i]) > r.max_abs_z && i < v.time_s.size()) r.time_s = v.time_s[i];
          r.max_abs_z = std::max(r.max_abs_z, std::abs(v.z[i]));
          sum += v.z[i];
          ++count;
        }
        ++i;
      }
      r.mean_z = count > 0 ? sum / count : 0.0;
      regions.push_back(r);
    }
  }
  return regions;
}

}  // namespace allanlab::experiments
