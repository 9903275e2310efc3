#include "estimators/fit/bandwidth_estimate.h"

#include <cmath>

#include <Eigen/Dense>

namespace allanlab::estimators {
namespace {
constexpr double kPeakFirstOrder = 0.301;   // tau_peak * fc, docs/theory.md §2.9
constexpr double kPeakButterworth2 = 0.468;
constexpr double kPeakPerTimeConstant = 1.8926;  // tau_peak / Tc for first order (docs/theory.md §2.6)
}  // namespace

BandwidthEstimate EstimateBandwidth(const AvarCurve& curve) {
  BandwidthEstimate e;
  const std::size_t n = curve.size();
  if (n < 5) {
    e.note = "fewer than 5 taus";
    return e;
  }
  // The largest ADEV before the curve first turns upward again (the short-tau region).
  std::size_t peak = 0;
  for (std::size_t i = 1; i < n; ++i) {
    if (curve.avar[i] > curve.avar[peak]) peak = i;
    if (i >= 2 && curve.avar[i] > curve.avar[i - 1] && curve.avar[i - 1] < curve.avar[i - 2]) break;
  }
  if (peak == 0) {
    e.note = "no short-tau maximum: the ADEV falls from the first tau (sampling too slow to see "
             "the band-limit, or its output averages it away)";
    return e;
  }
  if (peak + 2 >= n || peak < 2) {
    e.note = "the ADEV maximum is too close to the first tau to locate (needs 2 taus on each side)";
    return e;
  }
  // Weighted quadratic y = a + b x + c x^2 on x = ln tau, y = ln ADEV; Var(ln ADEV) = 1/(2 nu).
  Eigen::MatrixXd design(5, 3);
  Eigen::VectorXd y(5), w(5);
  for (int r = 0; r < 5; ++r) {
    const std::size_t i = peak - 2 + r;
    const double x = std::log(curve.tau_s[i]);
    design.row(r) << 1.0, x, x * x;
    y(r) = 0.5 * std::log(curve.avar[i]);
    w(r) = curve.edf.empty() ? 1.0 : 2.0 * curve.edf[i];
  }
  const Eigen::MatrixXd normal = design.transpose() * w.asDiagonal() * design;
  const Eigen::Vector3d coef = normal.ldlt().solve(design.transpose() * w.asDiagonal() * y);
  if (!(coef(2) < 0.0)) {
    e.note = "the ADEV around its maximum is not concave";
    return e;
  }
  // Without EDFs the residual scatter sets the scale of the covariance.
  Eigen::Matrix3d cov = normal.inverse();
  if (curve.edf.empty()) {
    const Eigen::VectorXd r = y - design * coef;
    cov *= r.squaredNorm() / 2.0;  // 5 points - 3 parameters
  }
  const double x_peak = -coef(1) / (2.0 * coef(2));
  // Gradient of x* = -b / (2c) with respect to (a, b, c).
  const Eigen::Vector3d grad(0.0, -1.0 / (2.0 * coef(2)), coef(1) / (2.0 * coef(2) * coef(2)));
  const double sigma_x = std::sqrt(std::max(grad.dot(cov * grad), 0.0));
  e.found = true;
  e.peak_tau_s = std::exp(x_peak);
  e.peak_tau_sigma_s = e.peak_tau_s * sigma_x;  // d tau = tau d(ln tau)
  e.cutoff_first_order_hz = kPeakFirstOrder / e.peak_tau_s;
  e.cutoff_first_order_sigma_hz = e.cutoff_first_order_hz * sigma_x;
  e.cutoff_butterworth2_hz = kPeakButterworth2 / e.peak_tau_s;
  e.cutoff_butterworth2_sigma_hz = e.cutoff_butterworth2_hz * sigma_x;
  e.time_constant_s = e.peak_tau_s / kPeakPerTimeConstant;
  e.time_constant_sigma_s = e.time_constant_s * sigma_x;
  return e;
}

}  // namespace allanlab::estimators
