#pragma once
// Ceres residuals of the Allan-variance sum model, one per tau, in the five scaled squared
// coefficients theta'_i (c_i^2 = scale_i theta'_i), each its own parameter block of size 1.
#include <array>
#include <cmath>

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

}  // namespace allanlab::estimators
