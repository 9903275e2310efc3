#include "experiments/diagnosis/profiled_step.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>
#include <boost/random/normal_distribution.hpp>

#include "sim/seeding.h"

namespace allanlab::experiments {
namespace {

constexpr std::uint64_t kProfileNullSeed = 0x70726f66696c65ULL;

Eigen::MatrixXd Toeplitz(const std::vector<double>& c) {
  const auto n = static_cast<Eigen::Index>(c.size());
  Eigen::MatrixXd m(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < n; ++j) m(i, j) = c[static_cast<std::size_t>(std::abs(i - j))];
  }
  return m;
}

// The profiled likelihood in the generalised eigenbasis: per kappa of the grid, the weights
// 1 / (1 + kappa lambda) and g^T W g of every regressor.
struct Profile {
  std::vector<double> kappas;
  Eigen::MatrixXd weights;  // n x kappas
  Eigen::VectorXd log_det;  // per kappa: sum ln(1 + kappa lambda)
  Eigen::MatrixXd g;        // regressors x n
  Eigen::MatrixXd gwg;      // regressors x kappas

  // Per regressor, the profiled statistic for y, and (when wanted) the size and sd at its kappa.
  Eigen::VectorXd Statistics(const Eigen::VectorXd& y, std::vector<ProfiledStep>* fits) const {
    const auto nk = static_cast<Eigen::Index>(kappas.size());
    Eigen::VectorXd best = Eigen::VectorXd::Constant(g.rows(), std::numeric_limits<double>::infinity());
    double best_null = std::numeric_limits<double>::infinity();
    const Eigen::VectorXd y2 = y.array().square();
    for (Eigen::Index k = 0; k < nk; ++k) {
      const double nll0 = log_det(k) + y2.dot(weights.col(k));
      best_null = std::min(best_null, nll0);
      const Eigen::VectorXd gwy = g * weights.col(k).cwiseProduct(y);
      for (Eigen::Index r = 0; r < g.rows(); ++r) {
        if (!(gwg(r, k) > 0.0)) continue;
        const double nll = nll0 - gwy(r) * gwy(r) / gwg(r, k);
        if (nll < best(r)) {
          best(r) = nll;
          if (fits) {
            (*fits)[static_cast<std::size_t>(r)].size = gwy(r) / gwg(r, k);
            (*fits)[static_cast<std::size_t>(r)].sd = 1.0 / std::sqrt(gwg(r, k));
          }
        }
      }
    }
    return (best_null - best.array()).cwiseMax(0.0);
  }
};

}  // namespace

bool ProfileSteps(const std::vector<double>& c0, const std::vector<double>& c_unit_rrw, double kappa_max,
                  const std::vector<double>& d, const std::vector<SparseRegressor>& regressors, int null_draws,
                  std::uint64_t null_stream, std::vector<ProfiledStep>* out, std::vector<double>* null_maxima) {
  constexpr double kGridStep = 0.1;  // log10 kappa: 26 % apart
  const Eigen::MatrixXd b = Toeplitz(c0);
  if (b.llt().info() != Eigen::Success) return false;
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(Toeplitz(c_unit_rrw), b);
  if (eig.info() != Eigen::Success) return false;
  const Eigen::VectorXd lambda = eig.eigenvalues().cwiseMax(0.0);
  const Eigen::MatrixXd& v = eig.eigenvectors();
  const auto n = static_cast<Eigen::Index>(d.size());
  const double top = lambda.maxCoeff();
  if (!(top > 0.0) || !(kappa_max > 0.0)) return false;
  Profile p;
  p.kappas = {0.0};
  for (double e = 0.0; kappa_max * std::pow(10.0, e) * top >= 1e-3; e -= kGridStep) {
    p.kappas.push_back(kappa_max * std::pow(10.0, e));
  }
  const auto nk = static_cast<Eigen::Index>(p.kappas.size());
  p.weights.resize(n, nk);
  p.log_det.resize(nk);
  for (Eigen::Index k = 0; k < nk; ++k) {
    const Eigen::VectorXd s = (p.kappas[static_cast<std::size_t>(k)] * lambda).array() + 1.0;
    p.weights.col(k) = s.cwiseInverse();
    p.log_det(k) = s.array().log().sum();
  }
  p.g = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(regressors.size()), n);
  for (std::size_t r = 0; r < regressors.size(); ++r) {
    for (const auto& [i, value] : regressors[r]) p.g.row(static_cast<Eigen::Index>(r)) += value * v.row(static_cast<Eigen::Index>(i));
  }
  p.gwg = p.g.array().square().matrix() * p.weights;
  out->assign(regressors.size(), ProfiledStep{});
  const Eigen::VectorXd y = v.transpose() * Eigen::Map<const Eigen::VectorXd>(d.data(), n);
  const Eigen::VectorXd t = p.Statistics(y, out);
  for (std::size_t r = 0; r < regressors.size(); ++r) (*out)[r].t = t(static_cast<Eigen::Index>(r));
  // Under the model (kappa = kappa_max) y ~ N(0, diag(1 + kappa_max lambda)).
  const Eigen::VectorXd sd = ((kappa_max * lambda).array() + 1.0).sqrt();
  sim::Engine engine = sim::MakeEngine(kProfileNullSeed, null_stream, 0);
  boost::random::normal_distribution<double> normal(0.0, 1.0);
  null_maxima->resize(static_cast<std::size_t>(null_draws));
  Eigen::VectorXd e(n);
  for (int draw = 0; draw < null_draws; ++draw) {
    for (Eigen::Index i = 0; i < n; ++i) e(i) = sd(i) * normal(engine);
    (*null_maxima)[static_cast<std::size_t>(draw)] = p.Statistics(e, nullptr).maxCoeff();
  }
  return true;
}

}  // namespace allanlab::experiments
