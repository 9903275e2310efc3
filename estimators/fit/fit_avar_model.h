#pragma once
// Coefficient extraction from an Allan-variance curve: one entry point, several methods.
//   kSlope:  the graphical slope method (slope_method.h), the biased baseline.
//   kWls:    weighted least squares on the Allan variance in the linear domain, the sum model
//            E[AVAR](tau) = sum_i c_i^2 S_i(tau) (seed paper eq. 3, with the exact discrete shapes
//            S_i of sim/), c_i^2 >= 0 as Ceres bounds, weights nu/(2 E^2) from the EDF, iterated
//            so that E comes from the fitted model (docs/theory.md §4.4 (i)).
//   kLogWls: the log-domain variant, weights nu/2, with the psi(nu/2) - ln(nu/2) bias removed
//            (docs/theory.md §4.4 (ii)).
//   kGls:    generalised least squares with the full covariance Omega of the overlapping AVAR
//            estimates across taus (avar_covariance.h, docs/theory.md §3.1), the consistent estimator
//            the GMWM literature calls for (Guerrier et al. 2013) without its wavelet detour.
//            Omega is computed ONCE from a pilot fit (log-WLS, whose weights nu/2 do not depend
//            on the model) and then held, as GMWM holds its weight matrix. Iterating Omega(theta)
//            to a fixed point is not a likelihood method: the quadratic cost r' Omega(theta)^-1 r
//            falls as Omega grows, and without the Gaussian ln det Omega(theta) term nothing
//            stops it, so on a misspecified curve the iteration inflates the flicker term (ADIS
//            16405 Gyro_X: B ~ 190 deg/h) and shrinks chi2 until it no longer flags the misfit
//            (MTi-G: 78 on 49 dof). A full Gaussian likelihood would fix that too but is not
//            convex, needs d Omega / d theta, and the AVAR estimates are chi-square-like rather
//            than Gaussian at long taus; two-step feasible GLS with a consistent pilot is
//            asymptotically as efficient. With Omega fixed the problem is linear: solved exactly
//            by non-negative least squares. Overlapping curves only: the covariance model is
//            built for overlapping starts (non-overlapping would need another pair count and is
//            not worth it: the overlapping estimator dominates it at every tau).
// Uncertainties: the covariance (S' W S)^{-1} of the squared coefficients (W = Omega^{-1} for
// GLS), propagated to c_i = sqrt(c_i^2) to first order; or, with FitUncertainty::kBootstrap, the
// spread of refits of curves simulated from the fitted model (parametric_bootstrap.h): the
// fitted terms only, no term selection in the replicates, the shapes and GLS covariance blocks
// shared by all replicates.
// WLS treats the taus as independent, which overlapping curves are not; the experiments measure
// how far that makes its error bars optimistic.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "estimators/fit/avar_curve.h"
#include "estimators/fit/noise_coefficient.h"
#include "estimators/fit/parametric_bootstrap.h"
#include "estimators/fit/slope_method.h"

namespace allanlab::estimators {

class AvarCovarianceModel;  // avar_covariance.h

enum class FitMethod { kSlope, kWls, kLogWls, kGls };
// Where the standard uncertainties come from (see the header comment).
enum class FitUncertainty { kCovariance, kBootstrap };

struct FitOptions {
  FitMethod method = FitMethod::kWls;
  std::vector<Coefficient> terms = {Coefficient::kQ, Coefficient::kN, Coefficient::kB,
                                    Coefficient::kK, Coefficient::kR};
  int max_reweightings = 25;         // weight iterations (model -> weights or covariance -> refit)
  double reweight_tolerance = 1e-5;  // stop when no squared coefficient moves more (relative)
  // Shapes: exact discrete expectations for the record (true) or IEEE 952 asymptotes (false).
  bool exact_shapes = true;
  // Term selection (WLS, log-WLS, GLS): every subset of `terms` scored by AIC on the fit's cost
  // with the weights (GLS: Omega) of the fit of all terms held, the lowest score kept
  // (linear_profile.h says why AIC and what it means as a test). A term left out, or at zero, is
  // reported by its 95 % profile-likelihood upper limit.
  bool select_terms = true;
  // kBootstrap: sigma = standard deviation of `bootstrap.trials` refits of simulated curves
  // (the slope method included, which has no covariance sigma of its own).
  FitUncertainty uncertainty = FitUncertainty::kCovariance;
  BootstrapOptions bootstrap;
  // Optional, GLS: the covariance model of this curve (its m, num_samples and sample period),
  // built with every term of `terms` (more are fine). Several fits of one curve (the band-limit
  // detection's plain and band-limited fits) then share one instead of each building its own,
  // ~0.1 s of CPU at 1e7 samples. Null: built when needed.
  std::shared_ptr<const AvarCovarianceModel> covariance;
  // false: no profile ranges (intervals and upper limits left unset; values and sigmas the same),
  // for fits of which only the values are read (the passes of an iterated refit).
  bool profile_ranges = true;
  bool IsValid(std::string* why) const;
};

struct CoefficientEstimate {
  bool asked = false;   // in options.terms
  bool fitted = false;  // asked, kept by term selection and not stuck at zero
  bool dropped = false;  // asked but left out by term selection (note and upper limit say more)
  double value_si = 0.0;
  double sigma_si = 0.0;  // standard uncertainty (0 when not fitted)
  double covariance_sigma_si = 0.0;  // the covariance sigma (= sigma_si unless bootstrapped)
  double bootstrap_bias_si = 0.0;    // mean of the replicates' values - value_si (bootstrap)
  // Profile-likelihood ranges (linear_profile.h), SI; the fits, not the slope method: the 68.3 %
  // and 95 % intervals (lower end 0 when the profile reaches the c^2 = 0 boundary first). A term
  // the data do not determine (left out by selection, or at zero) is not fitted (value and sigma
  // 0) and has its one-sided 95 % upper limit as well.
  bool has_intervals = false;
  std::array<double, 2> interval68_si{};
  std::array<double, 2> interval95_si{};
  bool has_upper_limit = false;
  double upper_limit_si = 0.0;
  std::string note;
};

struct FitSummary {
  FitMethod method = FitMethod::kWls;
  std::array<CoefficientEstimate, 5> coefficients;  // indexed by Coefficient
  const CoefficientEstimate& at(Coefficient c) const { return coefficients[static_cast<int>(c)]; }
  SlopeMethodResult slope;  // the slope-method reading, always computed for comparison
  int taus_used = 0;
  // The tau range of those taus, and what the fit did about a short-tau band-limit
  // (band_limited_fit.h; empty when not asked).
  double tau_min_s = 0.0, tau_max_s = 0.0;
  std::string band_limit;
  int iterations = 0;
  bool converged = false;
  // The fit's cost: the sum of squared weighted (GLS: whitened by the weight the fit held)
  // residuals at the solution, and P(chi2_dof >= chi2). What nested fits of one curve are compared
  // by (band-limit detection, AIC).
  double chi2 = 0.0;
  int dof = 0;  // taus - fitted coefficients
  double p_value = 1.0;
  // The goodness of fit, what IsPoorFit judges and the outputs print: GLS, the chosen model's
  // chi2 under its own covariance with chi-square marginals (GoodnessOfFitChi2,
  // linear_profile.h), and P(chi2_dof >= gof_chi2); the cost above for WLS and log-WLS. GLS
  // holds the weight of a pilot fit, whose small K made the long taus' variances too small:
  // judged by the cost, 25 of 200 records of white noise and a rate random walk had p < 1e-3
  // (docs/theory.md §4.8). Below kPoorFitP (POOR FIT in the message) the model does not describe
  // the curve; then coefficients and sigmas are those of the closest wrong model.
  double gof_chi2 = 0.0;
  double gof_p_value = 1.0;
  // The uncertainty actually reported: kBootstrap only if the bootstrap ran with >= 2 usable
  // replicates (otherwise the covariance sigmas stay and the message says why).
  FitUncertainty uncertainty = FitUncertainty::kCovariance;
  int bootstrap_trials = 0;  // replicates simulated
  int bootstrap_used = 0;    // replicates whose refit succeeded
  bool ok = false;
  std::string message;
};

// A poor fit: P(chi2_dof >= chi2) below kPoorFitP, i.e. chi2 above the 99.9 % quantile of chi2 on
// its dof (a right model is called poor in 1 record of 1000). The one threshold of every fit's
// POOR FIT message, ModelFitSummary::poor_fit (fit_model.h) and `allanlab fit`.
inline constexpr double kPoorFitP = 1e-3;
bool IsPoorFit(const FitSummary& s);  // dof > 0 and gof_p_value < kPoorFitP
// Sets chi2 and p_value from `chi2` on summary->dof, and the goodness of fit to the same.
void SetFitCost(double chi2, FitSummary* summary);
// Sets gof_chi2 and gof_p_value from `chi2` on summary->dof.
void SetGoodnessOfFit(double chi2, FitSummary* summary);
// The rule in words, for outputs: "chi2 above the 99.9 % quantile of chi2 on its dof (p < 0.001)".
std::string PoorFitRule();

// Returns summary->ok. A curve too short for the requested terms, invalid options or a solver
// failure give ok = false with a message; a fit that converged poorly is ok with
// converged = false and a message saying so.
bool FitAvarModel(const FitOptions& options, const AvarCurve& curve, FitSummary* summary);

// S_i(m) for unit coefficient c_i = 1 on the curve's record (exact or asymptotic).
std::vector<double> TermShape(Coefficient c, const AvarCurve& curve, bool exact);

}  // namespace allanlab::estimators
