#pragma once
// Covariance across taus of overlapping Allan-variance estimates under the IEEE sum model
// (docs/theory.md §3.1, Gaussian noise): what a generalised least-squares fit of the curve needs.
//
// With Y the integrated record (phase) and V(k) = E[(Y_{t+k} - Y_t)^2] its variogram, the Allan
// difference at start s is a lag-m second difference of Y, so
//   C(k) = Cov(D^{m1}_s, D^{m2}_{s+k}) = -1/(2 m1 m2) sum_{a,b=0..2} c_a c_b V(|k + b m2 - a m1|),
//   Cov(OAVAR(m1), OAVAR(m2)) = 1/(2 T1 T2) sum_k n(k) C(k)^2,
// n(k) the number of start pairs at lag k. V is linear in the squared coefficients, so the
// covariance is sum_ij theta_i theta_j G_ij, and the G_ij are computed once per curve.
// Quantization, white and random-walk noise give C(k) = 0 for |k| >= 2(m1 + m2); flicker has a
// tail C(k) ~ -m1 m2 R''(k), with R''(k) = -(B^2/pi) psi''(k + 1/2), summed on a geometric grid.
// Sums over more than 256 lags in the core are taken with a stride (relative error < 1e-3; the
// result is a weight and an error bar, not a reference value), except the products with
// quantization's C_Q, which is nonzero only at the isolated lags k = a m1 - b m2 and is summed
// there exactly. The ramp R is deterministic and adds no variance here.
#include <array>
#include <span>
#include <vector>

#include <Eigen/Dense>

#include "estimators/fit/avar_curve.h"
#include "estimators/fit/noise_coefficient.h"

namespace allanlab::estimators {

class AvarCovarianceModel {
 public:
  // Precondition: curve.IsValid(), overlapping estimator, curve.num_samples > 0.
  AvarCovarianceModel(const AvarCurve& curve, std::span<const Coefficient> terms);

  // Covariance matrix (taus x taus, (rad/s)^4) for squared SI coefficients theta[i] indexed by
  // Coefficient (entries of terms not in the model are ignored).
  Eigen::MatrixXd Covariance(const std::array<double, 5>& theta) const;

 private:
  std::vector<int> terms_;
  std::size_t taus_ = 0;
  // g_[i][j] for term indices (positions in terms_), i <= j.
  std::vector<std::vector<Eigen::MatrixXd>> g_;
};

}  // namespace allanlab::estimators
