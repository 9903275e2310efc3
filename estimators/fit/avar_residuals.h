#pragma once
// Ceres residuals of the Allan-variance sum model, one per tau, in the five scaled squared
// coefficients theta'_i (c_i^2 = scale_i theta'_i), each its own parameter block of size 1.
#include <array>
#include <cmath>
#include <utility>

#include <Eigen/Dense>
#include <ceres/ceres.h>

namespace allanlab::estimators {

// Linear domain: sqrt(w) (observed - sum_i shape_i theta'_i).
struct LinearAvarResidual {
  double observed = 0.0;
  double sqrt_weight = 1.0;
  std::array<double, 5> shape{};  // S_i(tau) * scale_i

  template <typename T>
  bool operator()(const T* q, const T* n, const T* b, const T* k, const T* r, T* residual) const {
    const T model = shape[0] * q[0] + shape[1] * n[0] + shape[2] * b[0] + shape[3] * k[0] +
                    shape[4] * r[0];
    residual[0] = sqrt_weight * (observed - model);
    return true;
  }
};

// Log domain: sqrt(nu/2) (log(observed) - bias - log(model)), bias = psi(nu/2) - ln(nu/2).
struct LogAvarResidual {
  double log_observed_unbiased = 0.0;
  double sqrt_weight = 1.0;
  std::array<double, 5> shape{};

  template <typename T>
  bool operator()(const T* q, const T* n, const T* b, const T* k, const T* r, T* residual) const {
    const T model = shape[0] * q[0] + shape[1] * n[0] + shape[2] * b[0] + shape[3] * k[0] +
                    shape[4] * r[0];
    if (!(model > T(0))) return false;  // Ceres treats the step as invalid and shrinks it
    using std::log;
    residual[0] = sqrt_weight * (log_observed_unbiased - log(model));
    return true;
  }
};

// GLS: all taus at once, whitened by W = L^{-1} (Omega = L L'): r = W a - (W S') theta'.
// Linear, so the Jacobian is analytic: d r / d theta'_i = -(W S')_i.
class WhitenedAvarResiduals : public ceres::CostFunction {
 public:
  // whitened_observed = W a; whitened_shapes.col(i) = W S_i scale_i (zero for absent terms).
  WhitenedAvarResiduals(Eigen::VectorXd whitened_observed, Eigen::MatrixXd whitened_shapes)
      : observed_(std::move(whitened_observed)), shapes_(std::move(whitened_shapes)) {
    set_num_residuals(static_cast<int>(observed_.size()));
    for (int i = 0; i < 5; ++i) mutable_parameter_block_sizes()->push_back(1);
  }
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    Eigen::Map<Eigen::VectorXd> r(residuals, observed_.size());
    r = observed_;
    for (int i = 0; i < 5; ++i) r -= shapes_.col(i) * parameters[i][0];
    if (jacobians) {
      for (int i = 0; i < 5; ++i) {
        if (!jacobians[i]) continue;
        Eigen::Map<Eigen::VectorXd>(jacobians[i], observed_.size()) = -shapes_.col(i);
      }
    }
    return true;
  }

 private:
  Eigen::VectorXd observed_;
  Eigen::MatrixXd shapes_;
};

}  // namespace allanlab::estimators
