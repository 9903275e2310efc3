#include "estimators/fit/profile_calibration.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include <boost/random/normal_distribution.hpp>

#include "estimators/fit/bounded_threshold.h"
#include "sim/seeding.h"

namespace allanlab::estimators {
namespace {

constexpr std::uint64_t kCalibrationSeed = 0x70726f66696c65ULL;
constexpr double kSearchTolerance = 1e-4;  // the ends' bisection under an interpolated ratio, relative

// min |y_r - A x|^2 over x >= 0 for each column y_r of `y`, A the columns `cols` of `a`: the
// unconstrained solution of one QR when it is feasible (most replicates), else NNLS.
Eigen::VectorXd MinChi2(const Eigen::MatrixXd& a, const std::vector<Eigen::Index>& cols,
                        const Eigen::MatrixXd& y) {
  if (cols.empty()) return y.colwise().squaredNorm().transpose();
  Eigen::MatrixXd sub(a.rows(), static_cast<Eigen::Index>(cols.size()));
  for (std::size_t c = 0; c < cols.size(); ++c) sub.col(static_cast<Eigen::Index>(c)) = a.col(cols[c]);
  const Eigen::MatrixXd x = sub.colPivHouseholderQr().solve(y);
  Eigen::VectorXd chi2(y.cols());
  for (Eigen::Index r = 0; r < y.cols(); ++r) {
    const Eigen::VectorXd xr = x.col(r).minCoeff() >= 0.0 ? Eigen::VectorXd(x.col(r))
                                                           : NonNegativeLeastSquares(sub, y.col(r));
    chi2(r) = (y.col(r) - sub * xr).squaredNorm();
  }
  return chi2;
}

}  // namespace

double EstimateSkewness(const LinearProblem& p, unsigned free_mask, int j) {
  if (p.whitening.size() == 0) return 0.0;
  Eigen::Index at = 0;
  const Eigen::MatrixXd sub = FreeColumns(p, free_mask, j, &at);
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

CalibrationRatio CalibrationRatioAt(const LinearProblem& p, unsigned free_mask, int j, double t) {
  CalibrationRatio out;
  const Eigen::VectorXd held = SolveHeld(p, free_mask, j, t);
  Eigen::MatrixXd w;
  if (!p.whitening_at || !p.whitening_at(held, &w)) return out;
  const Eigen::Index n = w.rows();
  const Eigen::MatrixXd a = w * p.design;
  // M M' = Omega_t for M = W^-1 (W' W = Omega_t^-1).
  const Eigen::MatrixXd m = w.fullPivLu().solve(Eigen::MatrixXd::Identity(n, n));
  const Eigen::VectorXd sd = m.rowwise().norm();
  const Eigen::VectorXd mean = p.design * held;
  sim::Engine engine = sim::MakeEngine(kCalibrationSeed, 0, 0);
  boost::random::normal_distribution<double> normal;
  // Per replicate, the curve with chi-square marginals and with Gaussian ones (the same
  // deviates): the ratio of their statistics' quantiles is the skew's effect alone (header).
  Eigen::MatrixXd z(n, kCalibrationReplicates);
  for (Eigen::Index r = 0; r < z.cols(); ++r) {
    for (Eigen::Index i = 0; i < n; ++i) z(i, r) = normal(engine);
  }
  const Eigen::MatrixXd g = m * z;
  Eigen::MatrixXd skewed_curves = g.colwise() + mean, gaussian_curves = skewed_curves;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!(mean(i) > 0.0) || !(sd(i) > 0.0)) continue;
    // E chi2_nu / nu with nu = 2 E^2 / Omega_ii: Wilson-Hilferty, (1 - a^2 + a u)^3 with
    // a^2 = 2 / (9 nu) and u = g / sd the standardised deviate.
    const double a2 = sd(i) * sd(i) / (9.0 * mean(i) * mean(i));
    for (Eigen::Index r = 0; r < z.cols(); ++r) {
      const double base = std::max(0.0, 1.0 - a2 + std::sqrt(a2) * g(i, r) / sd(i));
      skewed_curves(i, r) = mean(i) * base * base * base;
    }
  }
  std::vector<Eigen::Index> free_cols, held_cols;
  for (Eigen::Index k = 0; k < p.a.cols(); ++k) {
    if (!((free_mask >> k) & 1u)) continue;
    free_cols.push_back(k);
    if (k != j) held_cols.push_back(k);
  }
  auto statistics = [&](const Eigen::MatrixXd& curves) {
    const Eigen::MatrixXd y = w * curves;
    const Eigen::MatrixXd y_held = y.colwise() - t * a.col(j);
    const Eigen::VectorXd d = MinChi2(a, held_cols, y_held) - MinChi2(a, free_cols, y);
    return std::vector<double>(d.data(), d.data() + d.size());
  };
  std::vector<double> skewed = statistics(skewed_curves), gaussian = statistics(gaussian_curves);
  auto quantile = [](std::vector<double>& v, double level) {
    const auto k = static_cast<std::size_t>(std::ceil(level * kCalibrationReplicates)) - 1;
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
    return std::max(v[k], 0.0);
  };
  auto ratio = [&](double level) {
    const double reference = quantile(gaussian, level);
    return reference > 0.0 ? quantile(skewed, level) / reference : 1.0;
  };
  out.at68 = ratio(kProfileLevel68);
  out.at95 = ratio(kProfileLevel95);
  return out;
}

ProfileRanges CalibratedProfileIntervals(const LinearProblem& p, unsigned free_mask, int j, double offset) {
  const double sigma = ProfileStandardError(p, free_mask, j);
  if (!p.whitening_at || !(sigma > 0.0) || !std::isfinite(sigma) ||
      std::abs(EstimateSkewness(p, free_mask, j)) < kGaussianSkewness) {
    return {BoundedProfileInterval(p, free_mask, j, kProfileLevel68, offset),
            BoundedProfileInterval(p, free_mask, j, kProfileLevel95, offset)};
  }
  const ProfileRange gaussian68 = BoundedProfileInterval(p, free_mask, j, kProfileLevel68, offset);
  if (gaussian68.lower > 0.0) {
    // Off the boundary the ratio is 1 within the replicates' noise (header).
    return {gaussian68, BoundedProfileInterval(p, free_mask, j, kProfileLevel95, offset)};
  }
  const double t_hat = std::max(SolveSubset(p, free_mask)(j), 0.0);
  auto bounded = [sigma](double level, double t) {
    return BoundedLikelihoodRatioThreshold(level, std::max(t, 0.0) / sigma);
  };
  // The calibrated points, in t, shared by the two levels and both ends.
  std::vector<std::pair<double, CalibrationRatio>> points;
  auto ratio_at = [&](double level, double t) {
    auto read = [level](const CalibrationRatio& r) { return level == kProfileLevel68 ? r.at68 : r.at95; };
    if (points.empty()) return 1.0;
    if (t <= points.front().first) return read(points.front().second);
    for (std::size_t k = 1; k < points.size(); ++k) {
      if (t > points[k].first) continue;
      const double u = (t - points[k - 1].first) / (points[k].first - points[k - 1].first);
      return read(points[k - 1].second) + u * (read(points[k].second) - read(points[k - 1].second));
    }
    return read(points.back().second);
  };
  // One end: searched with the ratio interpolated between the points calibrated so far (none:
  // the Gaussian end), then calibrated there, until a calibrated point lies within kEndTolerance
  // of the end found (header).
  auto calibrate = [&](double t) {
    const CalibrationRatio c = CalibrationRatioAt(p, free_mask, j, t);
    points.insert(std::upper_bound(points.begin(), points.end(), t,
                                   [](double v, const auto& k) { return v < k.first; }),
                  {t, c});
  };
  auto end = [&](double level, bool upper) {
    // The lower end is 0 when the test at 0 accepts it: the ratio there is the smallest (K's
    // statistic at 0 is mostly 0 when its estimates are skewed), so it is calibrated first.
    if (!upper && t_hat > 0.0 && (points.empty() || points.front().first > 0.0)) calibrate(0.0);
    double e = 0.0;
    for (int round = 0; round <= kMaxCalibrations; ++round) {
      e = ProfileEnd(p, free_mask, j, [&](double t) { return ratio_at(level, t) * bounded(level, t) - offset; },
                     upper, kSearchTolerance);
      if (!std::isfinite(e) || (!upper && e <= 0.0) || round == kMaxCalibrations) break;
      const bool near = std::any_of(points.begin(), points.end(), [e](const auto& k) {
        return std::abs(k.first - e) <= kEndTolerance * std::max(e, k.first);
      });
      if (near) break;
      calibrate(e);
    }
    return e;
  };
  auto range = [&](double level) {
    ProfileRange r;
    r.upper = end(level, true);
    r.lower = end(level, false);
    return r;
  };
  return {range(kProfileLevel68), range(kProfileLevel95)};
}

}  // namespace allanlab::estimators
