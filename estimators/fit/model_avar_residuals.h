#pragma once
// Ceres residuals of a model with linear terms (scaled squared coefficients theta', analytic
// derivatives) and parametric terms (internal parameters u = ln(value), central differences),
// one residual per tau: parametric_fit.h describes the stages that use it.
#include <functional>
#include <vector>

#include <Eigen/Dense>
#include <ceres/ceres.h>

namespace allanlab::estimators {

// E(theta', u) = sum_i theta'_i shapes(u).col(i) + extra(u): what the residuals need of a model.
struct ModelAvarFunction {
  int linear = 0;     // size of theta'
  int nonlinear = 0;  // size of u
  // Fills shapes (taus x linear, scale included) and extra (taus) at u.
  std::function<void(const double* u, Eigen::MatrixXd* shapes, Eigen::VectorXd* extra)> evaluate;
};

class ModelAvarResiduals : public ceres::CostFunction {
 public:
  enum class Domain { kLinear, kLog };
  // kLinear: r = W (a - E); kLog: r = sqrt_w .* (log_target - ln E) with log_target = ln a - bias.
  // Parameter blocks: theta' (if linear > 0), then u (if nonlinear > 0).
  ModelAvarResiduals(ModelAvarFunction model, Domain domain, Eigen::VectorXd target,
                     Eigen::MatrixXd whitening)
      : model_(std::move(model)), domain_(domain), target_(std::move(target)), w_(std::move(whitening)) {
    set_num_residuals(static_cast<int>(target_.size()));
    if (model_.linear > 0) mutable_parameter_block_sizes()->push_back(model_.linear);
    if (model_.nonlinear > 0) mutable_parameter_block_sizes()->push_back(model_.nonlinear);
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const double* theta = model_.linear > 0 ? parameters[0] : nullptr;
    const double* u = model_.nonlinear > 0 ? parameters[model_.linear > 0 ? 1 : 0] : nullptr;
    const Eigen::Index n = target_.size();
    Eigen::MatrixXd shapes;
    Eigen::VectorXd e;
    if (!Residual(theta, u, &shapes, &e, residuals)) return false;
    if (!jacobians) return true;
    if (model_.linear > 0 && jacobians[0]) {
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> j(
          jacobians[0], n, model_.linear);
      if (domain_ == Domain::kLinear) {
        j = -w_ * shapes;
      } else {
        const Eigen::VectorXd g = -w_.diagonal().cwiseQuotient(e);
        j = g.asDiagonal() * shapes;
      }
    }
    const int ublock = model_.linear > 0 ? 1 : 0;
    if (model_.nonlinear > 0 && jacobians[ublock]) {
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> j(
          jacobians[ublock], n, model_.nonlinear);
      std::vector<double> up(u, u + model_.nonlinear);
      Eigen::VectorXd rp(n), rm(n);
      Eigen::MatrixXd s;
      Eigen::VectorXd ee;
      for (int q = 0; q < model_.nonlinear; ++q) {
        const double h = kStep;
        up[q] = u[q] + h;
        if (!Residual(theta, up.data(), &s, &ee, rp.data())) return false;
        up[q] = u[q] - h;
        if (!Residual(theta, up.data(), &s, &ee, rm.data())) return false;
        up[q] = u[q];
        j.col(q) = (rp - rm) / (2.0 * h);
      }
    }
    return true;
  }

  static constexpr double kStep = 1e-5;  // in ln(parameter): a relative step

 private:
  bool Residual(const double* theta, const double* u, Eigen::MatrixXd* shapes, Eigen::VectorXd* e,
                double* out) const {
    Eigen::VectorXd extra;
    model_.evaluate(u, shapes, &extra);
    *e = extra;
    for (int i = 0; i < model_.linear; ++i) *e += shapes->col(i) * theta[i];
    Eigen::Map<Eigen::VectorXd> r(out, target_.size());
    if (domain_ == Domain::kLinear) {
      r = w_ * (target_ - *e);
      return r.allFinite();
    }
    if ((e->array() <= 0.0).any()) return false;
    r = w_.diagonal().cwiseProduct(target_ - e->array().log().matrix());
    return r.allFinite();
  }

  ModelAvarFunction model_;
  Domain domain_;
  Eigen::VectorXd target_;
  Eigen::MatrixXd w_;  // whitening (kLinear) or diag(sqrt_w) (kLog)
};

}  // namespace allanlab::estimators
