#include "estimators/fit/profile_calibration.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <boost/random/normal_distribution.hpp>

#include "estimators/fit/bounded_threshold.h"
#include "sim/seeding.h"

namespace allanlab::estimators {
namespace {

constexpr std::uint64_t kCalibrationSeed = 0x70726f66696c65ULL;

double GaussianThreshold(const LinearProblem& p, unsigned free_mask, int j, double t, double level) {
  const double sigma = ProfileStandardError(p, free_mask, j);
  return BoundedLikelihoodRatioThreshold(level, sigma > 0.0 ? std::max(t, 0.0) / sigma : 1e300);
}

}  // namespace

double EstimateSkewness(const LinearProblem& p, unsigned free_mask, int j) {
  if (p.whitening.size() == 0) return 0.0;
  std::vector<Eigen::Index> cols;
  Eigen::Index at = 0;
  for (Eigen::Index k = 0; k < p.a.cols(); ++k) {
    if (!((free_mask >> k) & 1u)) continue;
    if (k == j) at = static_cast<Eigen::Index>(cols.size());
    cols.push_back(k);
  }
  Eigen::MatrixXd sub(p.a.rows(), static_cast<Eigen::Index>(cols.size()));
  for (std::size_t c = 0; c < cols.size(); ++c) sub.col(static_cast<Eigen::Index>(c)) = p.a.col(cols[c]);
  // x_hat_j = w' curve, w' the j-th row of (A'A)^-1 A' W0.
  const Eigen::MatrixXd gain = (sub.transpose() * sub).completeOrthogonalDecomposition().pseudoInverse() *
                               sub.transpose() * p.whitening;
  const Eigen::VectorXd w = gain.row(at).transpose();
  const Eigen::Index n = p.whitening.rows();
  const Eigen::MatrixXd m = p.whitening.fullPivLu().solve(Eigen::MatrixXd::Identity(n, n));
  const Eigen::VectorXd mean = p.design * SolveSubset(p, free_mask);
  double k2 = 0.0, k3 = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double var = m.row(i).squaredNorm();  // 2 E^2 / nu
    if (!(mean(i) > 0.0)) continue;
    // A chi-square-like estimate, E chi2_nu / nu: third cumulant 8 E^3 / nu^2 = 2 var^2 / E.
    k2 += w(i) * w(i) * var;
    k3 += w(i) * w(i) * w(i) * 2.0 * var * var / mean(i);
  }
  return k2 > 0.0 ? k3 / std::pow(k2, 1.5) : 0.0;
}

double CalibratedCriticalValue(const LinearProblem& p, unsigned free_mask, int j, double t, double level) {
  const Eigen::VectorXd held = SolveHeld(p, free_mask, j, t);
  Eigen::MatrixXd w;
  if (!p.whitening_at || !p.whitening_at(held, &w)) return GaussianThreshold(p, free_mask, j, t, level);
  const Eigen::Index n = w.rows();
  // M M' = Omega_t for M = W^-1 (W' W = Omega_t^-1).
  const Eigen::MatrixXd m = w.fullPivLu().solve(Eigen::MatrixXd::Identity(n, n));
  const Eigen::VectorXd sd = m.rowwise().norm();
  const Eigen::VectorXd mean = p.design * held;
  LinearProblem q;
  q.a = w * p.design;
  sim::Engine engine = sim::MakeEngine(kCalibrationSeed, 0, 0);
  boost::random::normal_distribution<double> normal;
  // Per replicate, the statistic with chi-square marginals and with Gaussian ones (the same
  // deviates): the ratio of their quantiles is the skew's effect alone (header).
  std::vector<double> skewed(kCalibrationReplicates), gaussian(kCalibrationReplicates);
  Eigen::VectorXd z(n), curve(n);
  auto statistic = [&](const Eigen::VectorXd& y) {
    q.y = w * y;
    return q.Chi2(SolveHeld(q, free_mask, j, t)) - q.Chi2(SolveSubset(q, free_mask));
  };
  for (int r = 0; r < kCalibrationReplicates; ++r) {
    for (Eigen::Index i = 0; i < n; ++i) z(i) = normal(engine);
    const Eigen::VectorXd g = m * z;
    for (Eigen::Index i = 0; i < n; ++i) {
      if (!(mean(i) > 0.0) || !(sd(i) > 0.0)) {
        curve(i) = mean(i) + g(i);
        continue;
      }
      // E chi2_nu / nu with nu = 2 E^2 / Omega_ii: Wilson-Hilferty, (1 - a^2 + a u)^3 with
      // a^2 = 2 / (9 nu) and u = g / sd the standardised deviate.
      const double a2 = sd(i) * sd(i) / (9.0 * mean(i) * mean(i));
      const double base = std::max(0.0, 1.0 - a2 + std::sqrt(a2) * g(i) / sd(i));
      curve(i) = mean(i) * base * base * base;
    }
    skewed[static_cast<std::size_t>(r)] = statistic(curve);
    gaussian[static_cast<std::size_t>(r)] = statistic(mean + g);
  }
  auto quantile = [level](std::vector<double>& v) {
    const auto k = static_cast<std::size_t>(std::ceil(level * kCalibrationReplicates)) - 1;
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
    return std::max(v[k], 0.0);
  };
  const double reference = quantile(gaussian);
  const double threshold = GaussianThreshold(p, free_mask, j, t, level);
  return reference > 0.0 ? threshold * quantile(skewed) / reference : threshold;
}

ProfileRange CalibratedProfileInterval(const LinearProblem& p, unsigned free_mask, int j, double level) {
  if (std::abs(EstimateSkewness(p, free_mask, j)) < kGaussianSkewness) {
    return BoundedProfileInterval(p, free_mask, j, level);
  }
  auto inside = [&](double t) {
    return ProfileStatistic(p, free_mask, j, t) <= CalibratedCriticalValue(p, free_mask, j, t, level);
  };
  auto gaussian = [&](double t) { return GaussianThreshold(p, free_mask, j, t, level); };
  const double t_hat = SolveSubset(p, free_mask)(j);
  constexpr double kTolerance = 1e-2;
  ProfileRange r;
  // Upper end: from the Gaussian one, widened until outside, then bisected against the estimate
  // (or the last accepted value).
  double lo = t_hat, hi = ProfileEnd(p, free_mask, j, gaussian, true);
  if (!std::isfinite(hi)) {
    r.upper = hi;
  } else {
    hi = std::max(hi, t_hat);
    if (hi <= 0.0) hi = 1.0 / std::max(p.a.col(j).squaredNorm(), 1e-300);
    int widen = 0;
    for (; widen < 60 && inside(hi); ++widen) {
      lo = hi;
      hi *= 2.0;
    }
    if (widen == 60) {
      r.upper = std::numeric_limits<double>::infinity();
    } else {
      for (int i = 0; i < 60 && hi - lo > kTolerance * hi; ++i) {
        const double mid = 0.5 * (lo + hi);
        (inside(mid) ? lo : hi) = mid;
      }
      r.upper = 0.5 * (lo + hi);
    }
  }
  // Lower end: 0 when 0 is accepted; else bisected between 0 and the estimate (the estimate held
  // inside as with the Gaussian threshold).
  if (inside(0.0)) {
    r.lower = 0.0;
    return r;
  }
  lo = 0.0;
  hi = t_hat > 0.0 ? t_hat : std::min(r.upper, ProfileEnd(p, free_mask, j, gaussian, true));
  for (int i = 0; i < 60 && hi - lo > kTolerance * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (inside(mid) ? hi : lo) = mid;
  }
  r.lower = 0.5 * (lo + hi);
  return r;
}

}  // namespace allanlab::estimators
