#include "estimators/estimate_distribution.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <tuple>

#include <Eigen/Dense>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/quadrature/ooura_fourier_integrals.hpp>
#include <boost/math/tools/roots.hpp>

#include "common/thread_memo.h"
#include "estimators/estimate_quantile_table.h"
#include "estimators/exact_quadratic_moments.h"
#include "sim/flicker_noise.h"
#include "sim/quantization_noise.h"
#include "sim/random_walk_rate.h"
#include "sim/white_rate_noise.h"

namespace allanlab::estimators {
namespace {

// Generalised autocovariance of unit power-law rate noise at lags 0..lags-1 (the scale cancels
// in the normalised weights), from the generators' own terms at tau0 = 1 s.
std::vector<double> PowerLawAutocovariance(int alpha, std::int64_t lags) {
  std::vector<double> r(static_cast<std::size_t>(lags), 0.0);
  switch (alpha) {
    case 0:
      sim::WhiteRateNoise{1.0}.FillAutocovariance(1.0, r);
      break;
    case -1:
      sim::FlickerNoise{1.0}.FillAutocovariance(1.0, r);
      break;
    case -2:
      sim::RandomWalkRate{1.0}.FillAutocovariance(1.0, r);
      break;
    case 2:
      sim::QuantizationNoise{1.0}.FillAutocovariance(1.0, r);
      break;
    case 1: {
      // Flicker phase x differenced: Cov(y_t, y_{t+k}) = 2 R_x(k) - R_x(k + 1) - R_x(|k - 1|).
      std::vector<double> phase(static_cast<std::size_t>(lags + 1), 0.0);
      sim::FlickerNoise{1.0}.FillAutocovariance(1.0, phase);
      for (std::int64_t k = 0; k < lags; ++k) {
        const auto i = static_cast<std::size_t>(k);
        r[i] = 2.0 * phase[i] - phase[i + 1] - phase[static_cast<std::size_t>(std::abs(k - 1))];
      }
      break;
    }
    default:
      r.clear();
  }
  return r;
}

bool NonOverlapping(Statistic s) {
  return s == Statistic::kAllanNonOverlapping || s == Statistic::kHadamardNonOverlapping;
}

}  // namespace

std::int64_t ReducedRecordLength(std::int64_t m, std::int64_t n_rate) {
  return std::llround(static_cast<double>(n_rate) * static_cast<double>(kReducedAveragingFactor) /
                      static_cast<double>(m));
}

std::vector<double> EstimateWeights(Statistic s, int alpha, std::int64_t m, std::int64_t n_rate,
                                    std::int64_t max_terms) {
  std::int64_t m_used = m, n_used = n_rate;
  if (m > kReducedAveragingFactor) {
    // Phase noise's differences decorrelate within a lag or two whatever m, so its estimate's
    // distribution depends on N itself, not on N/m, and a reduced record would misstate it.
    if (alpha > 0) return {};
    m_used = kReducedAveragingFactor;
    n_used = ReducedRecordLength(m, n_rate);
  }
  const std::vector<double> filter = DifferenceFilter(s, m_used);
  const std::int64_t count = TermCount(s, m_used, n_used);
  if (filter.empty() || count < 1 || count > max_terms || TermCount(s, m, n_rate) < 1) return {};
  const std::int64_t stride = NonOverlapping(s) ? m_used : 1;
  const auto length = static_cast<std::int64_t>(filter.size());
  const std::vector<double> r = PowerLawAutocovariance(alpha, (count - 1) * stride + length + 1);
  if (r.empty()) return {};

  // acf_c(j) = sum_i c_i c_{i+j}, then r_D(l) = sum_{|j|<L} acf_c(j) R(|l + j|)
  // (exact_quadratic_moments.h), in long double: the random walk's R grows like the lag.
  std::vector<long double> acf(static_cast<std::size_t>(length), 0.0L);
  for (std::int64_t j = 0; j < length; ++j) {
    for (std::int64_t i = 0; i + j < length; ++i) {
      acf[static_cast<std::size_t>(j)] += static_cast<long double>(filter[static_cast<std::size_t>(i)]) *
                                          filter[static_cast<std::size_t>(i + j)];
    }
  }
  std::vector<double> r_d(static_cast<std::size_t>(count), 0.0);
  for (std::int64_t k = 0; k < count; ++k) {
    const std::int64_t l = k * stride;
    long double sum = 0.0L;
    for (std::int64_t j = -(length - 1); j < length; ++j) {
      sum += acf[static_cast<std::size_t>(std::abs(j))] * r[static_cast<std::size_t>(std::abs(l + j))];
    }
    r_d[static_cast<std::size_t>(k)] = static_cast<double>(sum);
  }
  Eigen::MatrixXd covariance(count, count);
  for (std::int64_t a = 0; a < count; ++a) {
    for (std::int64_t b = 0; b < count; ++b) covariance(a, b) = r_d[static_cast<std::size_t>(std::abs(a - b))];
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(covariance, Eigen::EigenvaluesOnly);
  if (solver.info() != Eigen::Success) return {};
  std::vector<double> w(solver.eigenvalues().data(), solver.eigenvalues().data() + count);
  double total = 0.0;
  for (double& v : w) {
    v = std::max(v, 0.0);  // rounding leaves tiny negatives on a singular covariance
    total += v;
  }
  if (!(total > 0.0)) return {};
  for (double& v : w) v /= total;
  std::sort(w.begin(), w.end(), std::greater<>());
  while (!w.empty() && w.back() < 1e-14) w.pop_back();
  return w;
}

namespace {

// w chi-square(dof): the weights themselves (dof 1) or a lumped group of small ones.
struct Component {
  double weight = 0.0;
  double dof = 1.0;
};

std::vector<Component> Components(std::span<const double> weights) {
  std::vector<Component> c;
  for (double w : weights) c.push_back({w, 1.0});
  return c;
}

// Weights past the kept largest ones lumped in consecutive groups, each a scaled chi-square with
// the group's mean and variance (w = sum w^2 / sum w, dof = (sum w)^2 / sum w^2): the small weights
// shape only the centre of the distribution, and the CDF's cost is linear in the components.
std::vector<Component> Lumped(std::span<const double> descending, std::size_t kept = 24,
                              std::size_t groups = 4) {
  if (descending.size() <= kept + groups) return Components(descending);
  std::vector<Component> c = Components(descending.subspan(0, kept));
  const std::size_t rest = descending.size() - kept;
  for (std::size_t g = 0; g < groups; ++g) {
    double sum = 0.0, squares = 0.0;
    for (std::size_t i = kept + g * rest / groups; i < kept + (g + 1) * rest / groups; ++i) {
      sum += descending[i];
      squares += descending[i] * descending[i];
    }
    if (squares > 0.0) c.push_back({squares / sum, sum * sum / squares});
  }
  return c;
}

double ComponentCdf(std::span<const Component> components, double x) {
  if (!(x > 0.0)) return 0.0;
  // P(Q <= x) = 1/2 - (1/pi) int_0^inf sin(phi(u) - x u / 2) / (u rho(u)) du,
  // phi(u) = (1/2) sum dof_i atan(w_i u), rho(u) = prod (1 + w_i^2 u^2)^(dof_i / 4). With few
  // weights the integrand decays like u^(-1 - k/2) while it oscillates, so the sine of the
  // difference is split into two Fourier integrals of smooth, non-oscillating amplitudes, which
  // Ooura and Mori's double-exponential rule takes to high precision.
  auto amplitude = [&](double u, bool sine) {
    double phi = 0.0, log_rho = 0.0;
    for (const Component& c : components) {
      phi += 0.5 * c.dof * std::atan(c.weight * u);
      log_rho += 0.25 * c.dof * std::log1p(c.weight * c.weight * u * u);
    }
    return (sine ? std::sin(phi) : std::cos(phi)) / (u * std::exp(log_rho));
  };
  thread_local boost::math::quadrature::ooura_fourier_sin<double> fourier_sin(1e-7);
  thread_local boost::math::quadrature::ooura_fourier_cos<double> fourier_cos(1e-7);
  const double omega = 0.5 * x;
  const double cos_part = fourier_cos.integrate([&](double u) { return amplitude(u, true); }, omega).first;
  const double sin_part = fourier_sin.integrate([&](double u) { return amplitude(u, false); }, omega).first;
  return std::clamp(0.5 - (cos_part - sin_part) / M_PI, 0.0, 1.0);
}

// Root of the CDF, bracketed around chi-square(EDF)'s quantile (within a factor ~1.5 of it).
double ComponentQuantile(std::span<const Component> components, double p) {
  double mean = 0.0, squares = 0.0;
  for (const Component& c : components) {
    mean += c.dof * c.weight;
    squares += c.dof * c.weight * c.weight;
  }
  const double edf = mean * mean / squares;
  const double guess = mean * boost::math::quantile(boost::math::chi_squared(edf), p) / edf;
  double low = 0.6 * guess, high = 1.5 * guess;
  double f_low = ComponentCdf(components, low) - p, f_high = ComponentCdf(components, high) - p;
  while (f_low > 0.0 && low > 1e-12) f_low = ComponentCdf(components, low *= 0.5) - p;
  while (f_high < 0.0) f_high = ComponentCdf(components, high *= 2.0) - p;
  if (f_low > 0.0) return low;
  std::uintmax_t iterations = 100;
  const auto root = boost::math::tools::toms748_solve(
      [&](double x) { return ComponentCdf(components, x) - p; }, low, high, f_low, f_high,
      boost::math::tools::eps_tolerance<double>(26), iterations);
  return 0.5 * (root.first + root.second);
}

}  // namespace

double WeightedChiSquareCdf(std::span<const double> weights, double x) {
  return ComponentCdf(Components(weights), x);
}

double WeightedChiSquareQuantile(std::span<const double> weights, double p) {
  return ComponentQuantile(Components(weights), p);
}

EstimateQuantiles ComputeEstimateQuantiles(Statistic s, int alpha, std::int64_t m, std::int64_t n_rate,
                                           double confidence) {
  EstimateQuantiles q;
  const std::vector<double> weights = EstimateWeights(s, alpha, m, n_rate);
  if (!weights.empty() && confidence > 0.0 && confidence < 1.0) {
    const double p = 0.5 * (1.0 - confidence);
    const std::vector<Component> lumped = Lumped(weights);
    q = {true, ComponentQuantile(lumped, p), ComponentQuantile(lumped, 1.0 - p)};
  }
  return q;
}

EstimateQuantiles EstimateQuantilesAt(Statistic s, int alpha, std::int64_t m, std::int64_t n_rate,
                                      double confidence) {
  using Key = std::tuple<Statistic, int, std::int64_t, std::int64_t, double>;
  thread_local std::map<Key, EstimateQuantiles> remembered;
  return ThreadMemo(remembered, 1024, Key{s, alpha, m, n_rate, confidence}, [&] {
    const std::optional<EstimateQuantiles> tabulated = TabulatedEstimateQuantiles(s, alpha, m, n_rate, confidence);
    return tabulated ? *tabulated : ComputeEstimateQuantiles(s, alpha, m, n_rate, confidence);
  });
}

}  // namespace allanlab::estimators
