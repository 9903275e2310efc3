#include "estimators/fit/fit_avar_model.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

#include <Eigen/Dense>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/special_functions/digamma.hpp>
#include <ceres/ceres.h>

#include "estimators/fit/avar_covariance.h"
#include "estimators/fit/avar_residuals.h"
#include "estimators/fit/ceres_solver_options.h"
#include "estimators/fit/linear_profile.h"
#include "estimators/fit/whitening_cache.h"
#include "sim/sensor_model.h"

namespace allanlab::estimators {
namespace {

constexpr int kTerms = 5;

struct Problem {
  std::vector<int> asked;                       // coefficient indices in the fit
  std::array<std::vector<double>, kTerms> shape;  // S_i(tau_k)
  std::array<double, kTerms> scale{};           // c_i^2 = scale_i theta'_i
  std::vector<double> edf;
};

// Model E_k for scaled parameters theta'.
std::vector<double> Model(const Problem& p, const std::array<double, kTerms>& theta, std::size_t taus) {
  std::vector<double> e(taus, 0.0);
  for (int i : p.asked) {
    for (std::size_t k = 0; k < taus; ++k) e[k] += p.shape[i][k] * p.scale[i] * theta[i];
  }
  return e;
}

// Terms not asked are held at zero; asked ones are bounded below by zero (c^2 >= 0).
bool SolveBounded(const Problem& p, ceres::Problem* problem, std::array<double, kTerms>* theta,
                  std::string* why) {
  for (int i = 0; i < kTerms; ++i) {
    const bool asked = std::find(p.asked.begin(), p.asked.end(), i) != p.asked.end();
    if (!asked) {
      (*theta)[i] = 0.0;
      problem->SetParameterBlockConstant(&(*theta)[i]);
    } else {
      problem->SetParameterLowerBound(&(*theta)[i], 0, 0.0);
    }
  }
  const ceres::Solver::Options solver = FitSolverOptions(SolveKind::kLinearTerms, 500);
  ceres::Solver::Summary summary;
  ceres::Solve(solver, problem, &summary);
  if (!summary.IsSolutionUsable()) {
    if (why) *why = "Ceres: " + summary.message;
    return false;
  }
  return true;
}

// One weighted solve with Ceres; weights fixed from `expected` (linear) or nu (log).
bool Solve(const FitOptions& options, const AvarCurve& curve, const Problem& p,
           const std::vector<double>& expected, std::array<double, kTerms>* theta, std::string* why) {
  ceres::Problem problem;
  const std::size_t taus = curve.size();
  for (std::size_t k = 0; k < taus; ++k) {
    std::array<double, kTerms> shape{};
    for (int i : p.asked) shape[i] = p.shape[i][k] * p.scale[i];
    ceres::CostFunction* cost = nullptr;
    if (options.method == FitMethod::kLogWls) {
      const double half_nu = 0.5 * p.edf[k];
      auto* f = new LogAvarResidual;
      f->log_observed_unbiased =
          std::log(curve.avar[k]) - (boost::math::digamma(half_nu) - std::log(half_nu));
      f->sqrt_weight = std::sqrt(half_nu);
      f->shape = shape;
      cost = new ceres::AutoDiffCostFunction<LogAvarResidual, 1, 1, 1, 1, 1, 1>(f);
    } else {
      auto* f = new LinearAvarResidual;
      f->observed = curve.avar[k];
      f->sqrt_weight = std::sqrt(0.5 * p.edf[k]) / expected[k];
      f->shape = shape;
      cost = new ceres::AutoDiffCostFunction<LinearAvarResidual, 1, 1, 1, 1, 1, 1>(f);
    }
    problem.AddResidualBlock(cost, nullptr, &(*theta)[0], &(*theta)[1], &(*theta)[2], &(*theta)[3],
                             &(*theta)[4]);
  }
  return SolveBounded(p, &problem, theta, why);
}

// W = L^{-1} with Omega = L L' (a tiny ridge if Omega is numerically singular: adjacent
// overlapping taus are strongly correlated).
bool Whitening(const Eigen::MatrixXd& omega, Eigen::MatrixXd* w) {
  const Eigen::Index n = omega.rows();
  Eigen::MatrixXd regular = omega;
  for (double ridge = 0.0; ridge < 1e-3; ridge = ridge == 0.0 ? 1e-14 : ridge * 100.0) {
    if (ridge > 0.0) regular = omega + ridge * omega.diagonal().mean() * Eigen::MatrixXd::Identity(n, n);
    Eigen::LLT<Eigen::MatrixXd> llt(regular);
    if (llt.info() == Eigen::Success) {
      *w = llt.matrixL().solve(Eigen::MatrixXd::Identity(n, n));
      return true;
    }
  }
  return false;
}

// Solves the linear problem whitened by `w` (rows: taus) for the asked terms, theta' >= 0.
void SolveLinear(const AvarCurve& curve, const Problem& p, const Eigen::MatrixXd& w,
                 std::array<double, kTerms>* theta) {
  const auto taus = static_cast<Eigen::Index>(curve.size());
  const Eigen::VectorXd a = Eigen::Map<const Eigen::VectorXd>(curve.avar.data(), taus);
  Eigen::MatrixXd shapes(taus, static_cast<Eigen::Index>(p.asked.size()));
  for (std::size_t j = 0; j < p.asked.size(); ++j) {
    for (Eigen::Index k = 0; k < taus; ++k) {
      shapes(k, static_cast<Eigen::Index>(j)) = p.shape[p.asked[j]][k] * p.scale[p.asked[j]];
    }
  }
  const Eigen::VectorXd x = NonNegativeLeastSquares(w * shapes, w * a);
  theta->fill(0.0);
  for (std::size_t j = 0; j < p.asked.size(); ++j) (*theta)[p.asked[j]] = x(static_cast<Eigen::Index>(j));
}

}  // namespace

bool FitOptions::IsValid(std::string* why) const {
  if (terms.empty()) {
    if (why) *why = "fit: no terms requested";
    return false;
  }
  if (max_reweightings < 1) {
    if (why) *why = "fit: max_reweightings must be >= 1";
    return false;
  }
  if (uncertainty == FitUncertainty::kBootstrap && !bootstrap.IsValid(why)) return false;
  return true;
}

bool IsPoorFit(const FitSummary& s) { return s.dof > 0 && s.gof_p_value < kPoorFitP; }

namespace {
double ChiSquareTail(double chi2, int dof) {
  return dof > 0 ? boost::math::cdf(boost::math::complement(boost::math::chi_squared(dof), chi2)) : 1.0;
}
}  // namespace

void SetGoodnessOfFit(double chi2, FitSummary* summary) {
  summary->gof_chi2 = chi2;
  summary->gof_p_value = ChiSquareTail(chi2, summary->dof);
}

void SetFitCost(double chi2, FitSummary* summary) {
  summary->chi2 = chi2;
  summary->p_value = ChiSquareTail(chi2, summary->dof);
  SetGoodnessOfFit(chi2, summary);
}

std::string PoorFitRule() {
  std::ostringstream os;
  os << "chi2 above the " << 100.0 * (1.0 - kPoorFitP) << " % quantile of chi2 on its dof (p < " << kPoorFitP << ")";
  return os.str();
}

std::vector<double> TermShape(Coefficient c, const AvarCurve& curve, bool exact) {
  if (!exact || curve.num_samples <= 0) {
    std::vector<double> s;
    for (double tau : curve.tau_s) s.push_back(AsymptoteShape(c, tau));
    return s;
  }
  sim::SensorModel model;
  model.sample_clock = curve.sample_clock;
  model.terms = {TermFor(c, 1.0)};
  return model.ExpectedAvar(curve.m, {curve.num_samples, curve.estimator});
}

namespace {

// Work that depends on the curve and the requested terms only, shared by every fit of one
// FitAvarModel call (term selection refits many subsets): the exact term shapes and the GLS
// covariance model, built on first use.
class CurveCache {
 public:
  CurveCache(const AvarCurve& curve, const FitOptions& options) : curve_(curve), options_(options) {}

  const std::vector<double>& Shape(int i) {
    if (!has_shape_[i]) {
      shape_[i] = TermShape(static_cast<Coefficient>(i), curve_, options_.exact_shapes);
      has_shape_[i] = true;
    }
    return shape_[i];
  }
  // Built with every requested term; a subset's covariance passes zeros for the others.
  const AvarCovarianceModel& Covariance() {
    if (options_.covariance) return *options_.covariance;
    if (!covariance_) covariance_ = std::make_unique<AvarCovarianceModel>(curve_, options_.terms);
    return *covariance_;
  }
  // Builds everything fits with `fit` (a subset of the terms, no term selection) will ask for,
  // so that concurrent fits of curves with this geometry (bootstrap replicates) only read.
  void Prepare(const FitOptions& fit) {
    for (Coefficient c : fit.terms) Shape(static_cast<int>(c));
    if (fit.method == FitMethod::kGls) Covariance();
  }

 private:
  const AvarCurve& curve_;
  const FitOptions& options_;
  std::array<std::vector<double>, kTerms> shape_;
  std::array<bool, kTerms> has_shape_{};
  std::unique_ptr<AvarCovarianceModel> covariance_;
};

// `weight_model_si` (squared SI coefficients): weights (WLS) or covariance (GLS) fixed from this
// model instead of iterated, so that nested fits are compared under the same weights.
// `start_si` (squared SI coefficients): where the iterative log-WLS solve starts instead of the
// default; the linear methods are solved exactly and ignore it.
// `linear` (optional): the fit's cost as a linear problem in the asked terms' scaled squared
// coefficients (linear_profile.h), the asked term indices and their scales.
struct FixedFitProblem {
  LinearProblem problem;
  std::vector<int> asked;
  std::vector<double> scale;
};
bool FitFixedTerms(const FitOptions& options, const AvarCurve& curve, CurveCache* cache,
                   FitSummary* summary, const std::array<double, kTerms>* weight_model_si = nullptr,
                   const std::array<double, kTerms>* start_si = nullptr,
                   FixedFitProblem* linear = nullptr);

std::array<double, kTerms> SquaredCoefficients(const FitSummary& s) {
  std::array<double, kTerms> theta{};
  for (int i = 0; i < kTerms; ++i) {
    if (s.coefficients[i].fitted) theta[i] = s.coefficients[i].value_si * s.coefficients[i].value_si;
  }
  return theta;
}

// The fit of all asked terms, then the subset term selection and the profile ranges on its
// cost, all on one cache.
bool FitSelected(const FitOptions& options, const AvarCurve& curve, CurveCache* cache,
                 FitSummary* summary);
// Replaces the sigmas of the fitted coefficients by the bootstrap spread (header).
void Bootstrap(const FitOptions& options, const AvarCurve& curve, CurveCache* cache,
               FitSummary* summary);
}  // namespace

bool FitAvarModel(const FitOptions& options, const AvarCurve& curve, FitSummary* summary) {
  CurveCache cache(curve, options);
  if (!FitSelected(options, curve, &cache, summary)) return false;
  for (CoefficientEstimate& e : summary->coefficients) e.covariance_sigma_si = e.sigma_si;
  if (options.uncertainty == FitUncertainty::kBootstrap) Bootstrap(options, curve, &cache, summary);
  return true;
}

namespace {

void Bootstrap(const FitOptions& options, const AvarCurve& curve, CurveCache* cache,
               FitSummary* summary) {
  FitOptions refit = options;
  refit.select_terms = false;
  refit.uncertainty = FitUncertainty::kCovariance;
  refit.terms.clear();
  sim::SensorModel model;
  model.sample_clock = curve.sample_clock;
  for (Coefficient c : kAllCoefficients) {
    const CoefficientEstimate& e = summary->at(c);
    if (!e.fitted) continue;
    refit.terms.push_back(c);
    model.terms.push_back(TermFor(c, e.value_si));
  }
  std::string why;
  if (refit.terms.empty() || curve.num_samples <= 0 || !model.IsValid(&why)) {
    std::ostringstream os;
    os << "; bootstrap not run ("
       << (refit.terms.empty() ? "no fitted terms" : curve.num_samples <= 0 ? "record length unknown" : why.c_str())
       << "): covariance uncertainties";
    summary->message += os.str();
    return;
  }
  cache->Prepare(refit);
  const BootstrapSpread spread = ParametricBootstrap(
      model, curve, options.bootstrap, refit.terms.size(),
      [&](const AvarCurve& replicate, std::vector<double>* values, std::string* message) {
        FitSummary s;
        if (!FitFixedTerms(refit, replicate, cache, &s)) {
          *message = s.message;
          return false;
        }
        for (std::size_t j = 0; j < refit.terms.size(); ++j) {
          const CoefficientEstimate& e = s.at(refit.terms[j]);
          (*values)[j] = e.fitted ? e.value_si : 0.0;
        }
        return true;
      });
  summary->bootstrap_trials = spread.trials;
  summary->bootstrap_used = spread.used;
  std::ostringstream os;
  if (spread.used < 2) {
    os << "; bootstrap failed (" << spread.used << " of " << spread.trials
       << " replicates refitted; " << spread.first_failure << "): covariance uncertainties";
    summary->message += os.str();
    return;
  }
  for (std::size_t j = 0; j < refit.terms.size(); ++j) {
    CoefficientEstimate& e = summary->coefficients[static_cast<int>(refit.terms[j])];
    e.sigma_si = spread.sigma[j];
    e.bootstrap_bias_si = spread.mean[j] - e.value_si;
  }
  summary->uncertainty = FitUncertainty::kBootstrap;
  os << "; uncertainties from a parametric bootstrap (" << spread.used << " of " << spread.trials
     << " replicates, seed " << options.bootstrap.seed << ")";
  if (!spread.first_failure.empty()) os << "; first failed " << spread.first_failure;
  summary->message += os.str();
}

// Fills the summary's coefficients, chi2 and dof from the chosen subset masks.front() (bits:
// asked terms) of the problem: values and covariance sigmas of the terms it keeps above zero,
// upper limits of the others (their profile ranges: SetFitProfileRanges over all of `masks`, the
// choice and its competitive subsets, once chi2 and p are known).
void ReportSubset(const FixedFitProblem& fp, const std::vector<unsigned>& masks, bool selected,
                  FitSummary* summary) {
  const unsigned keep = masks.front();
  const LinearProblem& p = fp.problem;
  const Eigen::VectorXd x = SolveSubset(p, keep);
  // Covariance over every kept term, those at zero included (they are free in the fit: leaving
  // them out made the sigmas of the others 35 % smaller and the 68 % coverage of N 0.57).
  std::vector<Eigen::Index> positive, kept;
  for (std::size_t j = 0; j < fp.asked.size(); ++j) {
    if (!((keep >> j) & 1u)) continue;
    kept.push_back(static_cast<Eigen::Index>(j));
    if (x(static_cast<Eigen::Index>(j)) > 1e-12) positive.push_back(static_cast<Eigen::Index>(j));
  }
  Eigen::MatrixXd ap(p.a.rows(), static_cast<Eigen::Index>(kept.size()));
  for (std::size_t c = 0; c < kept.size(); ++c) ap.col(static_cast<Eigen::Index>(c)) = p.a.col(kept[c]);
  const Eigen::MatrixXd cov = (ap.transpose() * ap).completeOrthogonalDecomposition().pseudoInverse();
  for (std::size_t j = 0; j < fp.asked.size(); ++j) {
    CoefficientEstimate& e = summary->coefficients[fp.asked[j]];
    e = CoefficientEstimate{};
    e.asked = true;
    const auto at = std::find(kept.begin(), kept.end(), static_cast<Eigen::Index>(j));
    const double sigma_theta =
        at == kept.end() ? 0.0 : std::sqrt(std::max(cov(at - kept.begin(), at - kept.begin()), 0.0)) * fp.scale[j];
    if (std::find(positive.begin(), positive.end(), static_cast<Eigen::Index>(j)) != positive.end()) {
      e.fitted = true;
      e.value_si = std::sqrt(x(static_cast<Eigen::Index>(j)) * fp.scale[j]);
      e.sigma_si = sigma_theta / (2.0 * e.value_si);
    } else {
      e.sigma_si = std::sqrt(sigma_theta);  // kept at zero: the coefficient whose square is 1 sigma
      e.dropped = selected && !((keep >> j) & 1u);
      e.note = e.dropped ? "left out by the subset choice (AIC): the data do not determine it; 95 % upper limit given"
                         : "at zero: the data do not determine it; 95 % upper limit given";
    }
  }
  summary->chi2 = p.Chi2(x);
  summary->dof = summary->taus_used - static_cast<int>(positive.size());
}

bool FitSelected(const FitOptions& options, const AvarCurve& curve, CurveCache* cache,
                 FitSummary* summary) {
  if (options.method == FitMethod::kSlope) return FitFixedTerms(options, curve, cache, summary);
  FitOptions all = options;
  all.select_terms = false;
  FixedFitProblem fp;
  if (!FitFixedTerms(all, curve, cache, summary, nullptr, nullptr, &fp)) return false;
  const unsigned every = (1u << fp.asked.size()) - 1u;
  const std::vector<unsigned> masks =
      options.select_terms ? SelectSubsetByAic(fp.problem).competitive : std::vector<unsigned>{every};
  const unsigned keep = masks.front();
  const double full_chi2 = summary->chi2;
  ReportSubset(fp, masks, options.select_terms, summary);
  // The fit of all terms keeps its own chi2 (exact for log-WLS, whose problem here is the
  // expansion at that fit).
  SetFitCost(keep == every ? full_chi2 : summary->chi2, summary);
  JudgeGoodnessOfFit(fp.problem, masks, summary);
  if (options.profile_ranges) SetFitProfileRanges(fp.problem, masks, fp.asked, fp.scale, summary);
  std::string message = summary->converged ? "converged" : "weights did not settle within max_reweightings";
  if (options.select_terms && keep != every) {
    std::ostringstream os;
    os << "; terms chosen by AIC over all " << (every + 1) << " subsets with the weights of the fit of all terms held";
    message += os.str();
  }
  if (options.method == FitMethod::kLogWls) {
    message += "; log-WLS: subsets and profile ranges on the quadratic expansion of its cost";
  }
  summary->message = message;
  return true;
}

bool FitFixedTerms(const FitOptions& options, const AvarCurve& curve, CurveCache* cache,
                   FitSummary* summary, const std::array<double, kTerms>* weight_model_si,
                   const std::array<double, kTerms>* start_si, FixedFitProblem* linear) {
  *summary = FitSummary{};
  summary->method = options.method;
  std::string why;
  if (!options.IsValid(&why) || !curve.IsValid(&why)) {
    summary->message = why;
    return false;
  }
  summary->slope = ReadSlopes(curve);
  for (Coefficient c : options.terms) summary->coefficients[static_cast<int>(c)].asked = true;
  const std::size_t taus = curve.size();
  summary->taus_used = static_cast<int>(taus);

  if (options.method == FitMethod::kSlope) {
    for (Coefficient c : options.terms) {
      CoefficientEstimate& e = summary->coefficients[static_cast<int>(c)];
      const SlopeReading& r = summary->slope.at(c);
      e.fitted = r.found;
      e.value_si = r.value_si;
      e.note = r.note.empty() ? "slope method (no uncertainty)" : r.note;
    }
    summary->converged = summary->ok = true;
    return true;
  }

  Problem p;
  for (Coefficient c : options.terms) p.asked.push_back(static_cast<int>(c));
  std::sort(p.asked.begin(), p.asked.end());
  p.asked.erase(std::unique(p.asked.begin(), p.asked.end()), p.asked.end());
  if (taus < p.asked.size() + 1) {
    summary->message = "fit: " + std::to_string(taus) + " taus cannot support " +
                       std::to_string(p.asked.size()) + " terms (need at least one more tau)";
    return false;
  }
  p.edf = curve.edf;
  std::string edf_note;
  if (p.edf.empty()) {
    // No EDF with the curve: the non-overlapping cluster count K - 1 (IEEE 952's assumption).
    for (std::int64_t m : curve.m) {
      p.edf.push_back(std::max(1.0, static_cast<double>(curve.num_samples / m - 1)));
    }
    edf_note = " (no EDF given: weights from K - 1 clusters)";
  }
  for (int i : p.asked) {
    p.shape[i] = cache->Shape(i);
    double scale = 0.0;
    for (std::size_t k = 0; k < taus; ++k) {
      if (p.shape[i][k] > 0.0) {
        const double bound = curve.avar[k] / p.shape[i][k];
        scale = scale == 0.0 ? bound : std::min(scale, bound);
      }
    }
    p.scale[i] = scale > 0.0 ? scale : 1.0;
  }

  std::array<double, kTerms> theta{};
  for (int i : p.asked) theta[i] = start_si ? std::max((*start_si)[i], 0.0) / p.scale[i] : 0.1;
  std::vector<double> expected = curve.avar;  // first weights from the data
  if (weight_model_si) {
    expected.assign(taus, 0.0);
    for (int i = 0; i < kTerms; ++i) {
      if ((*weight_model_si)[i] <= 0.0) continue;
      const std::vector<double>& shape = cache->Shape(i);
      for (std::size_t k = 0; k < taus; ++k) expected[k] += (*weight_model_si)[i] * shape[k];
    }
    for (double& e : expected) e = std::max(e, 1e-300);
  }
  bool settled = false;
  int iteration = 0;
  Eigen::MatrixXd whitening;  // GLS only
  if (options.method == FitMethod::kGls) {
    if (curve.estimator != sim::AvarEstimatorKind::kOverlapping || curve.num_samples <= 0) {
      summary->message = "fit: GLS needs an overlapping Allan curve with its record length";
      return false;
    }
    // Omega is fixed at a pilot model and held (see the header): the log-domain WLS fit, whose
    // weights nu/2 do not depend on the model, or the caller's weight model in term selection.
    std::array<double, kTerms> anchor{};
    if (weight_model_si) {
      anchor = *weight_model_si;
    } else {
      FitOptions pilot = options;
      pilot.method = FitMethod::kLogWls;
      FitSummary pilot_summary;
      if (!FitFixedTerms(pilot, curve, cache, &pilot_summary)) {
        summary->message = "fit: the pilot log-WLS fit failed: " + pilot_summary.message;
        return false;
      }
      anchor = SquaredCoefficients(pilot_summary);
    }
    if (!Whitening(cache->Covariance().Covariance(anchor), &whitening)) {
      summary->message = "fit: the model covariance is not positive definite";
      return false;
    }
    SolveLinear(curve, p, whitening, &theta);
    iteration = 1;
    settled = true;
  } else if (options.method == FitMethod::kLogWls) {
    if (!Solve(options, curve, p, expected, &theta, &why)) {
      summary->message = "fit failed: " + why;
      return false;
    }
    iteration = 1;
    settled = true;
  } else {
    const int passes = weight_model_si ? 1 : options.max_reweightings;
    for (; iteration < passes && !settled; ++iteration) {
      const std::array<double, kTerms> before = theta;
      Eigen::VectorXd sqrt_w(static_cast<Eigen::Index>(taus));
      for (std::size_t k = 0; k < taus; ++k) sqrt_w(static_cast<Eigen::Index>(k)) = std::sqrt(0.5 * p.edf[k]) / expected[k];
      SolveLinear(curve, p, sqrt_w.asDiagonal().toDenseMatrix(), &theta);
      if (weight_model_si) {
        settled = true;
        continue;
      }
      expected = Model(p, theta, taus);
      for (double& e : expected) e = std::max(e, 1e-300);
      settled = iteration > 0;
      for (int i : p.asked) {
        if (std::abs(theta[i] - before[i]) > options.reweight_tolerance * std::max(theta[i], 1e-12)) {
          settled = false;
        }
      }
    }
  }
  summary->iterations = iteration;
  summary->converged = settled;

  // Covariance of theta' from the weighted design at the solution.
  const std::vector<double> model = Model(p, theta, taus);
  Eigen::MatrixXd a(taus, p.asked.size());
  Eigen::VectorXd whitened_residual(static_cast<Eigen::Index>(taus));
  double chi2 = 0.0;
  if (options.method == FitMethod::kGls) {
    Eigen::MatrixXd shapes(taus, p.asked.size());
    Eigen::VectorXd residual(taus);
    for (std::size_t k = 0; k < taus; ++k) {
      residual(static_cast<Eigen::Index>(k)) = curve.avar[k] - model[k];
      for (std::size_t j = 0; j < p.asked.size(); ++j) {
        shapes(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(j)) =
            p.shape[p.asked[j]][k] * p.scale[p.asked[j]];
      }
    }
    a = whitening * shapes;
    whitened_residual = whitening * residual;
    chi2 = whitened_residual.squaredNorm();
  }
  for (std::size_t k = 0; k < taus && options.method != FitMethod::kGls; ++k) {
    const double sqrt_w = options.method == FitMethod::kLogWls
                              ? std::sqrt(0.5 * p.edf[k]) / model[k]
                              : std::sqrt(0.5 * p.edf[k]) / expected[k];
    for (std::size_t j = 0; j < p.asked.size(); ++j) {
      a(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(j)) =
          sqrt_w * p.shape[p.asked[j]][k] * p.scale[p.asked[j]];
    }
    const double r = options.method == FitMethod::kLogWls
                         ? std::sqrt(0.5 * p.edf[k]) *
                               (std::log(curve.avar[k]) -
                                (boost::math::digamma(0.5 * p.edf[k]) - std::log(0.5 * p.edf[k])) -
                                std::log(model[k]))
                         : sqrt_w * (curve.avar[k] - model[k]);
    whitened_residual(static_cast<Eigen::Index>(k)) = r;
    chi2 += r * r;
  }
  if (linear) {
    // chi2(x) = |y - a x|^2: exact for WLS and GLS (weights held), the expansion at the solution
    // for log-WLS (a = -d residual / d theta').
    Eigen::VectorXd x(static_cast<Eigen::Index>(p.asked.size()));
    linear->asked = p.asked;
    linear->scale.clear();
    for (std::size_t j = 0; j < p.asked.size(); ++j) {
      x(static_cast<Eigen::Index>(j)) = theta[p.asked[j]];
      linear->scale.push_back(p.scale[p.asked[j]]);
    }
    linear->problem.a = a;
    linear->problem.y = whitened_residual + a * x;
    if (options.method == FitMethod::kGls) {
      // The profile's test at each held value under that value's covariance (linear_profile.h).
      Eigen::MatrixXd& design = linear->problem.design;
      design.resize(static_cast<Eigen::Index>(taus), static_cast<Eigen::Index>(p.asked.size()));
      for (std::size_t k = 0; k < taus; ++k) {
        for (std::size_t j = 0; j < p.asked.size(); ++j) {
          design(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(j)) = p.shape[p.asked[j]][k] * p.scale[p.asked[j]];
        }
      }
      linear->problem.target = Eigen::Map<const Eigen::VectorXd>(curve.avar.data(), static_cast<Eigen::Index>(taus));
      linear->problem.whitening = whitening;
      const AvarCovarianceModel* covariance = &cache->Covariance();
      linear->problem.whitening_at = CachedWhitening([covariance, asked = p.asked, scale = linear->scale](
                                                         const Eigen::VectorXd& x_scaled, Eigen::MatrixXd* w) {
        std::array<double, kTerms> theta{};
        for (std::size_t j = 0; j < asked.size(); ++j) {
          theta[asked[j]] = std::max(x_scaled(static_cast<Eigen::Index>(j)), 0.0) * scale[j];
        }
        return Whitening(covariance->Covariance(theta), w);
      });
    }
  }
  const Eigen::MatrixXd cov = (a.transpose() * a).completeOrthogonalDecomposition().pseudoInverse();
  int fitted = 0;
  for (std::size_t j = 0; j < p.asked.size(); ++j) {
    const int i = p.asked[j];
    CoefficientEstimate& e = summary->coefficients[i];
    const double theta_si = theta[i] * p.scale[i];
    const double sigma_theta = std::sqrt(std::max(cov(j, j), 0.0)) * p.scale[i];
    if (theta[i] <= 1e-12) {
      e.fitted = false;
      e.value_si = 0.0;
      e.sigma_si = std::sqrt(sigma_theta);
      e.note = "at zero: not supported by the data (sigma is the coefficient whose square is 1 sigma)";
      continue;
    }
    ++fitted;
    e.fitted = true;
    e.value_si = std::sqrt(theta_si);
    e.sigma_si = sigma_theta / (2.0 * e.value_si);
  }
  summary->dof = static_cast<int>(taus) - fitted;
  SetFitCost(chi2, summary);
  summary->ok = true;
  summary->message = (settled ? "converged" : "weights did not settle within max_reweightings") +
                     edf_note;
  return true;
}

}  // namespace

}  // namespace allanlab::estimators
