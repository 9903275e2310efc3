#include "estimators/fit/parametric_fit.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <memory>
#include <map>
#include <numbers>
#include <sstream>

#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/special_functions/digamma.hpp>

#include "estimators/fit/additive_term_avar.h"
#include "estimators/fit/avar_covariance.h"
#include "estimators/fit/ceres_solver_options.h"
#include "estimators/fit/linear_profile.h"
#include "estimators/fit/model_avar_residuals.h"
#include "estimators/fit/whitening_cache.h"
#include "sim/band_limited_avar.h"

namespace allanlab::estimators {
namespace {

// The profile of a linear term lets the nonlinear parameters (a band-limit's cutoff, a GM
// correlation time) move too, to first order: with v = u - u_hat free, min_v |y - A x - J_u v|^2 is
// |P (y - A x)|^2 with P the projector onto the complement of J_u's columns. Holding them at their
// fit instead made the ranges of the terms they trade with far too narrow: tactical_mems at
// 100 Hz (no quantization) gave Q = 0.50 urad with a 95 % interval [0.47, 0.54] while the
// covariance, which lets the 2nd-order cutoff move, gave +- 0.72. A parameter at its bound stays
// held (it cannot move to both sides).
template <class Jacobian>
void ProjectOutFreeParameters(const Jacobian& ju, const std::vector<double>& u, const std::vector<double>& u_lo,
                              const std::vector<double>& u_hi, LinearProblem* lp) {
  std::vector<Eigen::Index> free;
  for (std::size_t g = 0; g < u.size(); ++g) {
    if (u[g] > u_lo[g] + 1e-6 && u[g] < u_hi[g] - 1e-6) free.push_back(static_cast<Eigen::Index>(g));
  }
  if (free.empty()) return;
  Eigen::MatrixXd j(ju.rows(), static_cast<Eigen::Index>(free.size()));
  for (std::size_t c = 0; c < free.size(); ++c) j.col(static_cast<Eigen::Index>(c)) = ju.col(free[c]);
  const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(j);
  auto project = [&](const Eigen::MatrixXd& m) -> Eigen::MatrixXd { return m - j * cod.solve(m); };
  lp->a = project(lp->a);
  lp->y = project(lp->y);
}

constexpr int kTerms = 5;

double EdfAt(const AvarCurve& c, std::size_t k) {
  return c.edf.empty() ? std::max(1.0, static_cast<double>(c.num_samples / c.m[k] - 1)) : c.edf[k];
}

// The model pieces at u, cached per modifier parameters (the shapes of the linear terms change
// only with the band-limit).
class ModelPieces {
 public:
  ModelPieces(const AvarCurve& curve, std::vector<int> linear, std::vector<double> scale,
              std::vector<const ParametricTerm*> extra)
      : curve_(curve), linear_(std::move(linear)), scale_(std::move(scale)), extra_(std::move(extra)) {
    for (const ParametricTerm* t : extra_) {
      offset_.push_back(nonlinear_);
      nonlinear_ += static_cast<int>(t->parameters().size());
    }
  }
  int nonlinear() const { return nonlinear_; }
  // The linear terms' own (unfiltered) scaled shapes; filled by the first Evaluate().
  const Eigen::MatrixXd& Unfiltered() const { return unfiltered_; }
  const std::vector<int>& offsets() const { return offset_; }

  // SI parameters of extra term t from u.
  std::vector<double> Params(const double* u, std::size_t t) const {
    std::vector<double> p;
    const auto& specs = extra_[t]->parameters();
    for (std::size_t q = 0; q < specs.size(); ++q) {
      const double v = u[offset_[t] + static_cast<int>(q)];
      p.push_back(specs[q].log_scale ? std::exp(v) : v);
    }
    return p;
  }
  sim::SensorModel Base(const double* u) const {
    sim::SensorModel m;
    m.sample_clock = curve_.sample_clock;
    for (std::size_t t = 0; t < extra_.size(); ++t) {
      if (extra_[t]->modifies_other_terms()) extra_[t]->ApplyTo(Params(u, t), &m);
    }
    return m;
  }
  void Evaluate(const double* u, Eigen::MatrixXd* shapes, Eigen::VectorXd* extra) {
    const auto taus = static_cast<Eigen::Index>(curve_.size());
    const sim::SensorModel base = Base(u);
    if (unfiltered_.size() == 0) {
      // The linear terms' own exact shapes, computed once (the flicker one is O(N) per tau).
      unfiltered_.resize(taus, static_cast<Eigen::Index>(linear_.size()));
      sim::SensorModel m;
      m.sample_clock = base.sample_clock;
      for (std::size_t j = 0; j < linear_.size(); ++j) {
        m.terms = {TermFor(static_cast<Coefficient>(linear_[j]), 1.0)};
        const std::vector<double> e = ModelAvarOnCurve(m, curve_);
        for (Eigen::Index k = 0; k < taus; ++k) unfiltered_(k, static_cast<Eigen::Index>(j)) = e[k] * scale_[j];
      }
    }
    std::vector<double> key;
    if (base.band_limit.enabled()) key = {base.band_limit.cutoff_hz};
    auto it = shapes_.find(key);
    if (it == shapes_.end()) {
      Eigen::MatrixXd s = unfiltered_;
      if (base.band_limit.enabled()) {
        // Filtered = own exact shape + the band-limit's change (sim/band_limited_avar.h), so a new
        // cutoff costs O(len(q)) per tau and term.
        const std::shared_ptr<const sim::BandLimitChain> shared_chain =
            sim::SharedBandLimitChain(base.band_limit, base.sample_clock.rate_hz());
        const sim::BandLimitChain& chain = *shared_chain;
        std::vector<double> change;
        for (std::size_t j = 0; j < linear_.size(); ++j) {
          const sim::NoiseTerm term = TermFor(static_cast<Coefficient>(linear_[j]), 1.0);
          if (sim::BandLimitAvarChange(term, chain, curve_.sample_clock.period_s(), curve_.m, &change)) {
            for (Eigen::Index k = 0; k < taus; ++k) s(k, static_cast<Eigen::Index>(j)) += change[k] * scale_[j];
          } else {
            sim::SensorModel m = base;
            m.terms = {term};
            const std::vector<double> e = ModelAvarOnCurve(m, curve_);
            for (Eigen::Index k = 0; k < taus; ++k) s(k, static_cast<Eigen::Index>(j)) = e[k] * scale_[j];
          }
        }
      }
      if (shapes_.size() > 64) shapes_.clear();
      it = shapes_.emplace(key, s).first;
    }
    *shapes = it->second;
    extra->setZero(taus);
    if (!AdditiveExtra(u, key, base, extra)) {
      sim::SensorModel m = base;
      for (std::size_t t = 0; t < extra_.size(); ++t) {
        if (!extra_[t]->modifies_other_terms()) extra_[t]->ApplyTo(Params(u, t), &m);
      }
      if (!m.terms.empty()) {
        const std::vector<double> e = ModelAvarOnCurve(m, curve_);
        for (Eigen::Index k = 0; k < taus; ++k) (*extra)(k) = e[k];
      }
    }
  }

 private:
  // The additive terms' parts summed in term order from zero (additive_term_avar.h: the same
  // bits as one ModelAvarOnCurve of them all); false when a term is not a per-term part.
  bool AdditiveExtra(const double* u, const std::vector<double>& band_key, const sim::SensorModel& base,
                     Eigen::VectorXd* extra) {
    const auto taus = static_cast<Eigen::Index>(curve_.size());
    std::vector<std::vector<double>> parts;
    for (std::size_t t = 0; t < extra_.size(); ++t) {
      if (extra_[t]->modifies_other_terms()) continue;
      const std::vector<double>* part = additive_.Part(t, *extra_[t], Params(u, t), base, band_key);
      if (part == nullptr) return false;
      parts.push_back(*part);
    }
    for (const std::vector<double>& part : parts) {
      for (Eigen::Index k = 0; k < taus; ++k) (*extra)(k) += part[static_cast<std::size_t>(k)];
    }
    return true;
  }

  const AvarCurve& curve_;
  std::vector<int> linear_;
  std::vector<double> scale_;
  std::vector<const ParametricTerm*> extra_;
  std::vector<int> offset_;
  int nonlinear_ = 0;
  Eigen::MatrixXd unfiltered_;
  std::map<std::vector<double>, Eigen::MatrixXd> shapes_;
  AdditiveTermAvar additive_{curve_};
};

bool Whiten(const Eigen::MatrixXd& omega, Eigen::MatrixXd* w) {
  const Eigen::Index n = omega.rows();
  for (double ridge = 0.0; ridge < 1e-3; ridge = ridge == 0.0 ? 1e-14 : ridge * 100.0) {
    Eigen::LLT<Eigen::MatrixXd> llt(omega + ridge * omega.diagonal().mean() * Eigen::MatrixXd::Identity(n, n));
    if (llt.info() == Eigen::Success) {
      *w = llt.matrixL().solve(Eigen::MatrixXd::Identity(n, n));
      return true;
    }
  }
  return false;
}

// The GLS weight for the linear terms x (scaled, >= 0) with e the model's expectation and lin
// the linear terms' unfiltered one: Omega = D R D with R the correlation of the linear terms' exact
// covariance and D = e times its relative standard deviation (parametric_fit.h); the curve's
// EDFs (sqrt_half_nu) where no linear term but R is above 0 or lin is 0.
bool GlsWhitening(const AvarCovarianceModel& covariance, const std::vector<int>& linear,
                  const std::vector<double>& scale, const Eigen::VectorXd& x, const Eigen::VectorXd& e,
                  const Eigen::VectorXd& lin, const Eigen::VectorXd& sqrt_half_nu, Eigen::MatrixXd* w) {
  const Eigen::Index n = e.size();
  Eigen::VectorXd sd(n);
  for (Eigen::Index k = 0; k < n; ++k) sd(k) = std::max(e(k), 1e-300) / sqrt_half_nu(k);
  Eigen::MatrixXd r = Eigen::MatrixXd::Identity(n, n);
  std::array<double, kTerms> theta_si{};
  bool any = false;
  for (std::size_t j = 0; j < linear.size(); ++j) {
    theta_si[linear[j]] = std::max(x(static_cast<Eigen::Index>(j)), 0.0) * scale[j];
    any = any || (theta_si[linear[j]] > 0.0 && linear[j] != static_cast<int>(Coefficient::kR));
  }
  if (any) {
    const Eigen::MatrixXd omega = covariance.Covariance(theta_si);
    const Eigen::VectorXd d = omega.diagonal().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
    r = d.asDiagonal() * omega * d.asDiagonal();
    // Standard deviations: the expectation times the exact relative standard deviation of the
    // linear terms' estimates. The curve's own EDFs (`avar`'s) are optimistic at the longest
    // taus: with them a 1 h tg100 record gave K = 3.0 +- 0.66 deg/h/sqrt(h) (true 0), with these
    // 3.1 +- 1.4, as FitAvarModel's exact Omega does. The same relative standard deviation is
    // used where an additive term (GM, H, outliers) carries part of the curve, whose estimate
    // variance the model does not know: the alternative, the curve's own EDFs, measures chi2 in
    // another metric, so an extended model could not be compared with its nested IEEE fit
    // (ADIS16405 Gyro_X: IEEE+BW chi2 97 on 50 dof, the same with a GM term 132 on 48 with the GM
    // amplitude at zero).
    for (Eigen::Index k = 0; k < n; ++k) {
      if (lin(k) > 0.0) sd(k) = std::max(e(k), 1e-300) * std::sqrt(omega(k, k)) / lin(k);
    }
  }
  return Whiten(sd.asDiagonal() * r * sd.asDiagonal(), w);
}

struct Stage {
  bool usable = false;
  bool converged = false;
  int iterations = 0;
  std::string message;
};

Stage SolveStage(ModelAvarResiduals* cost, std::vector<double>* theta, std::vector<double>* u,
                 const std::vector<double>& u_lo, const std::vector<double>& u_hi, int max_iterations) {
  ceres::Problem::Options po;
  ceres::Problem problem(po);
  std::vector<double*> blocks;
  if (!theta->empty()) blocks.push_back(theta->data());
  if (!u->empty()) blocks.push_back(u->data());
  problem.AddResidualBlock(cost, nullptr, blocks);
  for (std::size_t i = 0; i < theta->size(); ++i) problem.SetParameterLowerBound(theta->data(), static_cast<int>(i), 0.0);
  for (std::size_t i = 0; i < u->size(); ++i) {
    problem.SetParameterLowerBound(u->data(), static_cast<int>(i), u_lo[i]);
    problem.SetParameterUpperBound(u->data(), static_cast<int>(i), u_hi[i]);
  }
  const ceres::Solver::Options so = FitSolverOptions(SolveKind::kParametric, max_iterations);
  ceres::Solver::Summary s;
  ceres::Solve(so, &problem, &s);
  Stage out;
  out.usable = s.IsSolutionUsable();
  out.converged = s.termination_type == ceres::CONVERGENCE;
  out.iterations = static_cast<int>(s.iterations.size());
  out.message = s.message;
  return out;
}

}  // namespace

bool ParametricFitOptions::IsValid(std::string* why) const {
  if (method == FitMethod::kSlope) {
    if (why) *why = "fit: parametric terms need a fit method (wls, logwls or gls), not slope";
    return false;
  }
  if (terms.empty() && extra.empty()) {
    if (why) *why = "fit: no terms requested";
    return false;
  }
  int modifiers = 0;
  for (const auto& t : extra) {
    if (!t) {
      if (why) *why = "fit: null parametric term";
      return false;
    }
    modifiers += t->modifies_other_terms() ? 1 : 0;
  }
  if (modifiers > 1) {
    if (why) *why = "fit: at most one band-limit term";
    return false;
  }
  if (max_iterations < 1) {
    if (why) *why = "fit: max_iterations must be >= 1";
    return false;
  }
  if (uncertainty == FitUncertainty::kBootstrap && !bootstrap.IsValid(why)) return false;
  return true;
}

std::vector<double> ModelAvarOnCurve(const sim::SensorModel& model, const AvarCurve& curve) {
  const sim::RecordShape shape{curve.num_samples, curve.estimator};
  return model.ExpectedAvar(curve.m, shape, sim::FlickerBandLimit::kStationaryChange);
}

namespace {

// Where a fit ended: the scaled linear terms, the parametric parameters (internal u) and the
// final stage's weight (GLS: its covariance model too).
struct FitEnd {
  std::vector<double> theta, u;
  Eigen::MatrixXd w;
  std::shared_ptr<const AvarCovarianceModel> covariance;
};
// The linear part of a fit as its profile ranges and term selection read it (linear_profile.h):
// the cost's expansion at the fit in the listed terms' squared coefficients (scaled: c^2 =
// scale[j] x_j), the parametric parameters free to first order; and where the fit ended.
struct LinearPart {
  LinearProblem problem;
  std::vector<LinearProblem> alternatives;  // at other cutoffs (CutoffAlternatives)
  std::vector<int> linear;  // Coefficient indices, ascending: the columns of problem
  std::vector<double> scale;
  FitEnd end;
};

// One fit with covariance uncertainties and without profile ranges (the body of
// FitAvarModelWithTerms), the linear terms of `held_zero` (bit j: linear[j]) held at zero; their
// columns stay in *part, so that their upper limits can be profiled. With `from` (the fit of
// every term of the same curve and options) the fit starts at its end and holds its weight, as
// FitAvarModel fits a subset with the weights of its fit of all terms held: terms already at zero
// there leave the fit where it was (a fresh pilot could settle elsewhere and move the weight).
bool FitOnce(const ParametricFitOptions& options, const AvarCurve& curve, unsigned held_zero,
             ParametricFitSummary* summary, LinearPart* part = nullptr, const FitEnd* from = nullptr);

// Replaces every fitted parameter's sigma by the bootstrap spread (parametric_bootstrap.h); the
// replicates refit the same model (the terms of held_zero held at zero).
void Bootstrap(const ParametricFitOptions& options, const AvarCurve& curve, unsigned held_zero,
               ParametricFitSummary* summary) {
  FitSummary& base = summary->base;
  ParametricFitOptions refit = options;
  refit.uncertainty = FitUncertainty::kCovariance;
  std::vector<int> linear;
  for (Coefficient c : kAllCoefficients) {
    if (base.at(c).asked) linear.push_back(static_cast<int>(c));
  }
  std::size_t parameters = linear.size();
  for (const ParametricEstimate& e : summary->extra) parameters += e.value_si.size();
  const sim::SensorModel model = FittedModel(options, curve, *summary);
  std::string why;
  if (model.terms.empty() || curve.num_samples <= 0 || !model.IsValid(&why)) {
    std::ostringstream os;
    os << "; bootstrap not run ("
       << (model.terms.empty() ? "nothing fitted" : curve.num_samples <= 0 ? "record length unknown" : why.c_str())
       << "): covariance uncertainties";
    base.message += os.str();
    return;
  }
  const std::vector<ParametricEstimate>& original = summary->extra;
  const BootstrapSpread spread = ParametricBootstrap(
      model, curve, options.bootstrap, parameters,
      [&](const AvarCurve& replicate, std::vector<double>* values, std::string* message) {
        ParametricFitSummary s;
        if (!FitOnce(refit, replicate, held_zero, &s)) {
          *message = s.base.message;
          return false;
        }
        std::size_t q = 0;
        for (int i : linear) {
          const CoefficientEstimate& e = s.base.coefficients[i];
          (*values)[q++] = e.fitted ? e.value_si : 0.0;
        }
        for (std::size_t t = 0; t < s.extra.size(); ++t) {
          if (original[t].fitted && !s.extra[t].fitted) {
            *message = s.extra[t].short_name;
            *message += " not fitted: ";
            *message += s.extra[t].note;
            return false;
          }
          for (double v : s.extra[t].value_si) (*values)[q++] = v;
        }
        return true;
      });
  base.bootstrap_trials = spread.trials;
  base.bootstrap_used = spread.used;
  std::ostringstream os;
  if (spread.used < 2) {
    os << "; bootstrap failed (" << spread.used << " of " << spread.trials
       << " replicates refitted; " << spread.first_failure << "): covariance uncertainties";
    base.message += os.str();
    return;
  }
  std::size_t q = 0;
  for (int i : linear) {
    CoefficientEstimate& e = base.coefficients[i];
    if (e.fitted) {
      e.sigma_si = spread.sigma[q];
      e.bootstrap_bias_si = spread.mean[q] - e.value_si;
    }
    ++q;
  }
  for (ParametricEstimate& e : summary->extra) {
    e.bootstrap_bias_si.assign(e.value_si.size(), 0.0);
    for (std::size_t k = 0; k < e.value_si.size(); ++k, ++q) {
      if (!e.fitted) continue;
      e.sigma_si[k] = spread.sigma[q];
      e.bootstrap_bias_si[k] = spread.mean[q] - e.value_si[k];
    }
  }
  base.uncertainty = FitUncertainty::kBootstrap;
  os << "; uncertainties from a parametric bootstrap (" << spread.used << " of " << spread.trials
     << " replicates, seed " << options.bootstrap.seed << ")";
  if (!spread.first_failure.empty()) os << "; first failed " << spread.first_failure;
  base.message += os.str();
}

}  // namespace

bool FitAvarModelWithTerms(const ParametricFitOptions& options, const AvarCurve& curve,
                           ParametricFitSummary* summary) {
  LinearPart part;
  if (!FitOnce(options, curve, 0u, summary, &part)) return false;
  bool stopped = false;
  for (const ParametricEstimate& e : summary->extra) stopped = stopped || !e.fitted;
  stopped = stopped && options.stop_without_start;
  auto keep_covariance_sigmas = [summary] {
    for (CoefficientEstimate& e : summary->base.coefficients) e.covariance_sigma_si = e.sigma_si;
    for (ParametricEstimate& e : summary->extra) e.covariance_sigma_si = e.sigma_si;
  };
  if (stopped) {
    keep_covariance_sigmas();
    return true;
  }
  const unsigned every = (1u << part.linear.size()) - 1u;
  std::vector<unsigned> masks = {every};
  unsigned held_zero = 0;
  if (options.select_terms && !part.linear.empty()) {
    // The subsets scored on the fit of all terms (header), as FitAvarModel scores them with the
    // weights of its fit of all terms held; the choice refitted exactly.
    const SubsetChoice choice = SelectSubsetByAic(part.problem);
    masks = choice.competitive;
    if (choice.mask != every) {
      ParametricFitSummary chosen;
      LinearPart chosen_part;
      bool usable = FitOnce(options, curve, every & ~choice.mask, &chosen, &chosen_part, &part.end);
      for (const ParametricEstimate& e : chosen.extra) usable = usable && e.fitted;
      if (usable) {
        *summary = chosen;
        part = chosen_part;
        held_zero = every & ~choice.mask;
        std::ostringstream os;
        os << "; terms chosen by AIC over all " << (every + 1u)
           << " subsets on the fit of all terms (its weights held, the parametric parameters free)";
        summary->base.message += os.str();
      } else {
        masks = {every};  // the chosen subset cannot be fitted: every term kept, as without selection
      }
    }
    for (std::size_t j = 0; j < part.linear.size(); ++j) {
      CoefficientEstimate& e = summary->base.coefficients[part.linear[j]];
      if (!((held_zero >> j) & 1u)) continue;
      e.dropped = true;
      e.note = "left out by the subset choice (AIC): the data do not determine it; 95 % upper limit given";
    }
  }
  JudgeGoodnessOfFit(part.problem, masks, &summary->base);
  if (options.profile_ranges) {
    SetFitProfileRanges(part.problem, masks, part.linear, part.scale, &summary->base, part.alternatives);
  }
  keep_covariance_sigmas();
  if (options.uncertainty == FitUncertainty::kBootstrap) Bootstrap(options, curve, held_zero, summary);
  return true;
}

namespace {

// The GLS whitening of the curve's covariance under the model x (scaled linear terms) with the
// linear terms' shapes and the additive terms' AVAR fixed (linear_profile.h: whitening_at),
// cached by the bits of x (whitening_cache.h).
std::function<bool(const Eigen::VectorXd&, Eigen::MatrixXd*)> WhiteningAt(
    const std::shared_ptr<const AvarCovarianceModel>& covariance, const Eigen::MatrixXd& shapes,
    const Eigen::VectorXd& extra, const Eigen::MatrixXd& unfiltered, const std::vector<int>& linear,
    const std::vector<double>& scale, const Eigen::VectorXd& sqrt_half_nu) {
  return CachedWhitening([covariance, shapes, extra, unfiltered, linear, scale, sqrt_half_nu](const Eigen::VectorXd& x,
                                                                                              Eigen::MatrixXd* wx) {
    const Eigen::VectorXd held = x.cwiseMax(0.0);
    return GlsWhitening(*covariance, linear, scale, held, shapes * held + extra, unfiltered * held, sqrt_half_nu,
                        wx);
  });
}

// The linear problem at other cutoffs of a band-limit that is the fit's one parametric term
// (linear_profile.h: alternative problems), the weight w held: steps of kCutoffStep in log
// frequency outwards from the fit's cutoff on both sides, each side up to the cutoff's bound or
// to the first step whose minimum (the fit's terms free) lies more than kCutoffReach above the
// fit's. Outwards because the shapes at a new cutoff are the costly part (a low cutoff's chain is
// long): a well-resolved cutoff costs two steps. Scanning every step to the bounds instead cost
// 1.7 s per fit on 1 h records at 100 Hz and moved none of the ranges in the test (a second
// valley beyond a barrier was not seen). At most kMaxAlternatives are kept, spread evenly over
// the steps found, the outermost included. Empty when the fit has other parametric
// parameters or its cutoff is at a bound. *range_u: the cutoff's own 95 % profile range (log
// frequency) read off the same steps: the outermost step within kProfileDelta95 of the fit's
// minimum, or the crossing beyond it (linear in the root of the offset); {u, u} when empty.
constexpr double kCutoffStep = 0.15;                    // in log frequency: 16 %
constexpr double kCutoffReach = 2.0 * kProfileDelta95;  // SetProfileRanges keeps those below kProfileDelta95
constexpr int kMaxCutoffSteps = 40;                     // per side
constexpr std::size_t kMaxAlternatives = 8;
std::vector<LinearProblem> CutoffAlternatives(ModelPieces* pieces, const std::vector<const ParametricTerm*>& active,
                                              const std::vector<double>& u, const std::vector<double>& u_lo,
                                              const std::vector<double>& u_hi, const Eigen::MatrixXd& w,
                                              const Eigen::VectorXd& curve,
                                              const std::shared_ptr<const AvarCovarianceModel>& covariance,
                                              const std::vector<int>& linear, const std::vector<double>& scale,
                                              const Eigen::VectorXd& sqrt_half_nu, unsigned held_zero,
                                              const LinearProblem& fit, std::array<double, 2>* range_u) {
  std::vector<LinearProblem> out;
  *range_u = {u.empty() ? 0.0 : u[0], u.empty() ? 0.0 : u[0]};
  if (linear.empty() || u.size() != 1 || active.size() != 1 || !active[0]->modifies_other_terms() ||
      !(u[0] > u_lo[0] + 1e-6 && u[0] < u_hi[0] - 1e-6)) {
    return out;
  }
  const unsigned fitted = ((1u << linear.size()) - 1u) & ~held_zero;
  if (fitted == 0u) return out;
  const double fit_chi2 = fit.Chi2(SolveSubset(fit, fitted));
  std::vector<std::pair<double, LinearProblem>> found;  // by cutoff
  for (double side : {-1.0, 1.0}) {
    double last_u = u[0], last_offset = 0.0;
    double& end = (*range_u)[side < 0.0 ? 0 : 1];
    for (int k = 1; k <= kMaxCutoffSteps; ++k) {
      const double ug = std::clamp(u[0] + side * kCutoffStep * k, u_lo[0], u_hi[0]);
      Eigen::MatrixXd shapes;
      Eigen::VectorXd extra;
      pieces->Evaluate(&ug, &shapes, &extra);
      LinearProblem alternative;
      alternative.a = w * shapes;
      alternative.y = w * (curve - extra);
      const double offset = alternative.Chi2(SolveSubset(alternative, fitted)) - fit_chi2;
      if (offset < kProfileDelta95) {
        end = ug;
      } else if (last_offset < kProfileDelta95) {
        // The crossing, in the root of the offset, which is linear in the cutoff near a minimum.
        const double root_last = std::sqrt(std::max(last_offset, 0.0));
        const double f = (std::sqrt(kProfileDelta95) - root_last) / std::max(std::sqrt(offset) - root_last, 1e-300);
        end = last_u + std::clamp(f, 0.0, 1.0) * (ug - last_u);
      }
      last_u = ug;
      last_offset = offset;
      if (!(offset < kCutoffReach)) break;
      if (covariance) {
        alternative.design = shapes;
        alternative.target = curve - extra;
        alternative.offset = extra;
        alternative.whitening_at =
            WhiteningAt(covariance, shapes, extra, pieces->Unfiltered(), linear, scale, sqrt_half_nu);
      }
      found.emplace_back(ug, std::move(alternative));
      if (ug == u_lo[0] || ug == u_hi[0]) break;
    }
  }
  std::sort(found.begin(), found.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  const std::size_t keep = std::min(found.size(), kMaxAlternatives);
  for (std::size_t k = 0; k < keep; ++k) {
    const std::size_t at = keep == 1 ? 0 : k * (found.size() - 1) / (keep - 1);
    out.push_back(std::move(found[at].second));
  }
  return out;
}

bool FitOnce(const ParametricFitOptions& options, const AvarCurve& curve, unsigned held_zero,
             ParametricFitSummary* summary, LinearPart* part, const FitEnd* from) {
  *summary = ParametricFitSummary{};
  FitSummary& base = summary->base;
  base.method = options.method;
  std::string why;
  if (!options.IsValid(&why) || !curve.IsValid(&why)) {
    base.message = why;
    return false;
  }
  if (options.method == FitMethod::kGls &&
      (curve.estimator != sim::AvarEstimatorKind::kOverlapping || curve.num_samples <= 0)) {
    base.message = "fit: GLS needs an overlapping Allan curve with its record length";
    return false;
  }
  base.slope = ReadSlopes(curve);
  const std::size_t taus = curve.size();
  base.taus_used = static_cast<int>(taus);

  // 1. Baseline: the linear terms alone (log-WLS).
  std::vector<int> linear;
  for (Coefficient c : options.terms) linear.push_back(static_cast<int>(c));
  std::sort(linear.begin(), linear.end());
  linear.erase(std::unique(linear.begin(), linear.end()), linear.end());
  for (int i : linear) base.coefficients[i].asked = true;
  std::vector<double> baseline_e(taus, 0.0);
  sim::SensorModel without;
  without.sample_clock = curve.sample_clock;
  std::array<double, kTerms> baseline_si{};
  if (!linear.empty()) {
    FitOptions b;
    b.method = FitMethod::kLogWls;
    b.terms = options.terms;
    b.select_terms = false;
    FitSummary bs;
    if (!FitAvarModel(b, curve, &bs)) {
      base.message = "fit: the baseline fit failed: " + bs.message;
      return false;
    }
    for (int i : linear) {
      if (!bs.coefficients[i].fitted) continue;
      baseline_si[i] = bs.coefficients[i].value_si * bs.coefficients[i].value_si;
      without.terms.push_back(TermFor(static_cast<Coefficient>(i), bs.coefficients[i].value_si));
    }
    baseline_e = ModelAvarOnCurve(without, curve);
  }
  std::vector<double> residual(taus);
  for (std::size_t k = 0; k < taus; ++k) residual[k] = curve.avar[k] - baseline_e[k];

  // Parametric terms with a starting point.
  std::vector<const ParametricTerm*> active;
  std::vector<std::size_t> active_index;
  std::vector<double> u0, u_lo, u_hi;
  summary->extra.resize(options.extra.size());
  for (std::size_t t = 0; t < options.extra.size(); ++t) {
    const ParametricTerm& term = *options.extra[t];
    ParametricEstimate& pe = summary->extra[t];
    pe.id = std::string(term.id());
    pe.short_name = std::string(term.short_name());
    pe.parameters = term.parameters();
    pe.value_si.assign(pe.parameters.size(), 0.0);
    pe.sigma_si.assign(pe.parameters.size(), 0.0);
    std::vector<double> start, lo, hi;
    std::string reason;
    if (!term.InitialGuess(curve, residual, without, &start, &reason)) {
      pe.note = "not fitted: " + reason;
      continue;
    }
    term.Bounds(curve, &lo, &hi);
    for (std::size_t q = 0; q < start.size(); ++q) {
      const bool log_scale = pe.parameters[q].log_scale;
      u0.push_back(log_scale ? std::log(start[q]) : start[q]);
      u_lo.push_back(log_scale ? std::log(lo[q]) : lo[q]);
      u_hi.push_back(log_scale ? std::log(hi[q]) : hi[q]);
    }
    active.push_back(&term);
    active_index.push_back(t);
  }
  if (options.stop_without_start && active.size() < options.extra.size()) {
    base.ok = summary->ok = true;
    base.message = "stopped: a parametric term has no starting point (screening)";
    return true;
  }
  const std::size_t n_params = linear.size() + u0.size();
  if (taus < n_params + 1) {
    std::ostringstream os;
    os << "fit: " << taus << " taus cannot support " << n_params << " parameters (need at least one more tau)";
    base.message = os.str();
    return false;
  }

  // Scales: c_i^2 = scale_i theta'_i with theta' ~ 1 where the term reaches the curve.
  std::vector<double> scale;
  for (int i : linear) {
    const std::vector<double> s = TermShape(static_cast<Coefficient>(i), curve, true);
    double sc = 0.0;
    for (std::size_t k = 0; k < taus; ++k) {
      if (s[k] > 0.0) sc = sc == 0.0 ? curve.avar[k] / s[k] : std::min(sc, curve.avar[k] / s[k]);
    }
    scale.push_back(sc > 0.0 ? sc : 1.0);
  }
  ModelPieces pieces(curve, linear, scale, active);
  ModelAvarFunction function;
  function.linear = static_cast<int>(linear.size());
  function.nonlinear = pieces.nonlinear();
  // The model the fit sees: the terms held at zero have no shape (their theta' stays at 0).
  // `every_term`, the same with every shape, gives the expansion their profiles read.
  ModelAvarFunction every_term = function;
  every_term.evaluate = [&pieces](const double* u, Eigen::MatrixXd* s, Eigen::VectorXd* e) {
    pieces.Evaluate(u, s, e);
  };
  function.evaluate = [&pieces, held_zero](const double* u, Eigen::MatrixXd* s, Eigen::VectorXd* e) {
    pieces.Evaluate(u, s, e);
    for (Eigen::Index j = 0; j < s->cols(); ++j) {
      if ((held_zero >> j) & 1u) s->col(j).setZero();
    }
  };
  std::vector<double> theta(linear.size()), u = u0;
  for (std::size_t j = 0; j < linear.size(); ++j) {
    theta[j] = (held_zero >> j) & 1u ? 0.0 : std::max(baseline_si[linear[j]] / scale[j], 1e-3);
  }
  // The same terms have started (same baseline), so `from` has their sizes; checked all the same.
  if (from && (from->theta.size() != theta.size() || from->u.size() != u.size())) from = nullptr;
  if (from) {
    u = from->u;
    for (std::size_t j = 0; j < linear.size(); ++j) theta[j] = (held_zero >> j) & 1u ? 0.0 : from->theta[j];
  }

  // 2. Pilot on log residuals.
  const auto n = static_cast<Eigen::Index>(taus);
  Eigen::VectorXd log_target(n), sqrt_half_nu(n), a(n);
  for (std::size_t k = 0; k < taus; ++k) {
    const double half_nu = 0.5 * EdfAt(curve, k);
    const auto kk = static_cast<Eigen::Index>(k);
    log_target(kk) = std::log(curve.avar[k]) - (boost::math::digamma(half_nu) - std::log(half_nu));
    sqrt_half_nu(kk) = std::sqrt(half_nu);
    a(kk) = curve.avar[k];
  }
  // From a fit's end with its weight held (linear domain), the pilot is that fit's.
  const bool pilot = !from || options.method == FitMethod::kLogWls;
  Stage stage;
  stage.usable = stage.converged = true;
  if (pilot) {
    auto* log_cost = new ModelAvarResiduals(function, ModelAvarResiduals::Domain::kLog, log_target,
                                            sqrt_half_nu.asDiagonal().toDenseMatrix());
    stage = SolveStage(log_cost, &theta, &u, u_lo, u_hi, options.max_iterations);
    if (!stage.usable) {
      base.message = "fit failed (pilot): Ceres: " + stage.message;
      return false;
    }
  }
  int iterations = stage.iterations;
  Eigen::MatrixXd w = sqrt_half_nu.asDiagonal().toDenseMatrix();
  Eigen::VectorXd target = log_target;
  ModelAvarResiduals::Domain domain = ModelAvarResiduals::Domain::kLog;

  // 3. Final stage with weights fixed at the pilot.
  std::shared_ptr<const AvarCovarianceModel> covariance;  // GLS
  if (options.method != FitMethod::kLogWls) {
    Eigen::MatrixXd s;
    Eigen::VectorXd e;
    pieces.Evaluate(u.empty() ? nullptr : u.data(), &s, &e);
    for (std::size_t j = 0; j < linear.size(); ++j) e += s.col(static_cast<Eigen::Index>(j)) * theta[j];
    const Eigen::Map<const Eigen::VectorXd> x(theta.data(), static_cast<Eigen::Index>(theta.size()));
    if (!pilot) {
      w = from->w;
      covariance = from->covariance;
    } else if (options.method == FitMethod::kWls) {
      w = (e.cwiseMax(1e-300).cwiseQuotient(sqrt_half_nu)).cwiseInverse().asDiagonal().toDenseMatrix();
    } else {
      covariance = options.covariance ? options.covariance
                                      : std::make_shared<const AvarCovarianceModel>(curve, options.terms);
      if (!GlsWhitening(*covariance, linear, scale, x, e, pieces.Unfiltered() * x, sqrt_half_nu, &w)) {
        base.message = "fit: the pilot covariance is not positive definite";
        return false;
      }
    }
    target = a;
    domain = ModelAvarResiduals::Domain::kLinear;
    auto* cost = new ModelAvarResiduals(function, domain, target, w);
    stage = SolveStage(cost, &theta, &u, u_lo, u_hi, options.max_iterations);
    if (!stage.usable) {
      base.message = "fit failed: Ceres: " + stage.message;
      return false;
    }
    iterations += stage.iterations;
    // The linear terms at the exact minimum of this cost with the parametric parameters held: a
    // non-negative least-squares problem. Ceres stops on a relative cost change, which on a poor
    // fit (chi2 ~ 5e5, ADIS16405 Gyro_Z) leaves the linear terms where the cost is still several
    // units above that minimum: the profile ranges, taken about the minimum, then missed the
    // reported value (K = 369 with a 95 % interval [109, 251]).
    if (!linear.empty()) {
      Eigen::MatrixXd s;
      Eigen::VectorXd extra;
      function.evaluate(u.empty() ? nullptr : u.data(), &s, &extra);
      const Eigen::VectorXd x = NonNegativeLeastSquares(w * s, w * (a - extra));
      for (std::size_t j = 0; j < linear.size(); ++j) theta[j] = x(static_cast<Eigen::Index>(j));
    }
  }

  // Residuals and Jacobian at the solution; covariance (J'J)^-1.
  ModelAvarResiduals final_cost(every_term, domain, target, w);
  const int blocks = (linear.empty() ? 0 : 1) + (u.empty() ? 0 : 1);
  std::vector<const double*> params;
  if (!linear.empty()) params.push_back(theta.data());
  if (!u.empty()) params.push_back(u.data());
  Eigen::VectorXd res(n);
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  RowMajor jl(n, std::max<Eigen::Index>(1, static_cast<Eigen::Index>(linear.size())));
  RowMajor ju(n, std::max<Eigen::Index>(1, static_cast<Eigen::Index>(u.size())));
  std::vector<double*> jac;
  if (!linear.empty()) jac.push_back(jl.data());
  if (!u.empty()) jac.push_back(ju.data());
  (void)blocks;
  if (!final_cost.Evaluate(params.data(), res.data(), jac.data())) {
    base.message = "fit: the model cannot be evaluated at the solution";
    return false;
  }
  const auto p_all = static_cast<Eigen::Index>(linear.size() + u.size());
  Eigen::MatrixXd j(n, p_all);
  if (!linear.empty()) j.leftCols(static_cast<Eigen::Index>(linear.size())) = jl;
  if (!u.empty()) j.rightCols(static_cast<Eigen::Index>(u.size())) = ju;
  // The covariance of the model fitted: the terms held at zero are not in it.
  for (std::size_t q = 0; q < linear.size(); ++q) {
    if ((held_zero >> q) & 1u) j.col(static_cast<Eigen::Index>(q)).setZero();
  }
  const Eigen::MatrixXd cov = (j.transpose() * j).completeOrthogonalDecomposition().pseudoInverse();

  int fitted = 0;
  // Profile ranges of the linear terms, the parametric parameters free to first order
  // (linear_profile.h: the cost's expansion in theta', A = -d res / d theta'; the projection above).
  LinearProblem lp;
  lp.a = -jl.leftCols(static_cast<Eigen::Index>(linear.size()));
  lp.y = res + lp.a * Eigen::Map<const Eigen::VectorXd>(theta.data(), static_cast<Eigen::Index>(theta.size()));
  ProjectOutFreeParameters(ju, u, u_lo, u_hi, &lp);
  if (covariance && !linear.empty()) {
    // GLS: each held value is tested under its own model's covariance, as FitAvarModel's profile
    // does (linear_profile.h), with the parametric parameters held at their fit and, to first
    // order, free (projected out at each held value as above). Holding the pilot's weight along
    // the profile tested a larger B against the small long-tau variances of a model with a
    // smaller one: under a fitted band-limit B's upper ends fell short (docs/theory.md §4.7).
    Eigen::MatrixXd shapes;
    Eigen::VectorXd extra;
    pieces.Evaluate(u.empty() ? nullptr : u.data(), &shapes, &extra);
    lp.design = shapes;
    lp.target = a - extra;
    lp.offset = extra;
    std::vector<Eigen::Index> free;
    for (std::size_t g = 0; g < u.size(); ++g) {
      if (u[g] > u_lo[g] + 1e-6 && u[g] < u_hi[g] - 1e-6) free.push_back(static_cast<Eigen::Index>(g));
    }
    if (!free.empty()) {
      Eigen::MatrixXd jf(n, static_cast<Eigen::Index>(free.size()));
      for (std::size_t c = 0; c < free.size(); ++c) jf.col(static_cast<Eigen::Index>(c)) = ju.col(free[c]);
      lp.free_directions = w.colPivHouseholderQr().solve(jf);  // ju = -W dE/du
    }
    lp.whitening_at = WhiteningAt(covariance, shapes, extra, pieces.Unfiltered(), linear, scale, sqrt_half_nu);
  }
  std::vector<LinearProblem> alternatives;
  std::array<double, 2> cutoff_range_u{};
  if (part && options.profile_ranges && domain == ModelAvarResiduals::Domain::kLinear) {
    alternatives = CutoffAlternatives(&pieces, active, u, u_lo, u_hi, w, a, covariance, linear, scale,
                                      sqrt_half_nu, held_zero, lp, &cutoff_range_u);
  }
  for (std::size_t q = 0; q < linear.size(); ++q) {
    CoefficientEstimate& ce = base.coefficients[linear[q]];
    const double theta_si = theta[q] * scale[q];
    const double sigma_theta = std::sqrt(std::max(cov(static_cast<Eigen::Index>(q), static_cast<Eigen::Index>(q)), 0.0)) * scale[q];
    if (theta[q] <= 1e-12) {
      ce.fitted = false;
      ce.sigma_si = std::sqrt(sigma_theta);  // the coefficient whose square is 1 sigma
      ce.note = "at zero: the data do not determine it; 95 % upper limit given";
    } else {
      ++fitted;
      ce.fitted = true;
      ce.value_si = std::sqrt(theta_si);
      ce.sigma_si = sigma_theta / (2.0 * ce.value_si);
    }
  }
  for (std::size_t t = 0; t < active.size(); ++t) {
    ParametricEstimate& pe = summary->extra[active_index[t]];
    pe.fitted = true;
    const std::vector<double> values = pieces.Params(u.data(), t);
    for (std::size_t q = 0; q < values.size(); ++q) {
      const auto idx = static_cast<Eigen::Index>(linear.size()) + pieces.offsets()[t] + static_cast<Eigen::Index>(q);
      const double su = std::sqrt(std::max(cov(idx, idx), 0.0));
      pe.value_si[q] = values[q];
      pe.sigma_si[q] = pe.parameters[q].log_scale ? values[q] * su : su;
      if (!alternatives.empty() || cutoff_range_u[0] != cutoff_range_u[1]) {
        pe.interval95_si.resize(values.size(), {0.0, 0.0});
        pe.interval95_si[q] = {std::exp(cutoff_range_u[0]), std::exp(cutoff_range_u[1])};
      }
      const std::size_t g = static_cast<std::size_t>(idx) - linear.size();
      if (u[g] <= u_lo[g] + 1e-6 || u[g] >= u_hi[g] - 1e-6) {
        pe.note += (pe.note.empty() ? "" : "; ") + pe.parameters[q].name + " at its bound";
      }
      ++fitted;
    }
  }
  base.dof = static_cast<int>(taus) - fitted;
  SetFitCost(res.squaredNorm(), &base);
  base.iterations = iterations;
  base.converged = stage.converged;
  if (part) *part = {std::move(lp), std::move(alternatives), linear, scale, {theta, u, w, covariance}};
  base.ok = summary->ok = true;
  std::ostringstream os;
  os << (stage.converged ? "converged" : "Ceres did not converge: " + stage.message);
  base.message = os.str();
  return true;
}

}  // namespace

sim::SensorModel FittedModel(const ParametricFitOptions& options, const AvarCurve& curve,
                             const ParametricFitSummary& summary) {
  sim::SensorModel m;
  m.sample_clock = curve.sample_clock;
  for (Coefficient c : kAllCoefficients) {
    const CoefficientEstimate& e = summary.base.at(c);
    if (e.fitted) m.terms.push_back(TermFor(c, e.value_si));
  }
  for (std::size_t t = 0; t < options.extra.size() && t < summary.extra.size(); ++t) {
    if (summary.extra[t].fitted) options.extra[t]->ApplyTo(summary.extra[t].value_si, &m);
  }
  return m;
}

}  // namespace allanlab::estimators
