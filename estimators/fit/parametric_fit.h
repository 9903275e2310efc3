#pragma once
// One fit of the linear IEEE 952 terms (c_i^2 >= 0) together with parametric terms
// (parametric_term.h: Gauss-Markov, harmonic, band-limit, ...): the entry the sim-to-real
// diagnosis (experiments/diagnosis/) uses to try candidate effects on top of a baseline model.
//
// The model is a sim::SensorModel built from the parameters, so its expected AVAR is sim/'s exact
// one (band-limit and finite record included). Stages:
//   1. baseline: the linear terms alone by log-WLS; its residual seeds each parametric term's
//      InitialGuess;
//   2. pilot: all parameters by Ceres on the log-domain residuals sqrt(nu/2)(ln a - bias - ln E),
//      whose weights do not depend on the model;
//   3. final (kWls, kGls): linear-domain residuals whitened by a weight matrix fixed at the pilot
//      (as in fit_avar_model.h: never iterated, see there why). kWls: diagonal nu/(2 E_pilot^2).
//      kGls: Omega = D R D with R the correlation matrix of the exact covariance of the pilot's
//      linear terms (avar_covariance.h) and D = diag(E_pilot sqrt(2/nu)) (the pilot's variances,
//      parametric terms included). nu: the curve's EDFs with additive parametric terms (their
//      estimates' variances are not in the covariance model); with the band-limit alone the
//      exact covariance's own, 2 E_lin^2 / Omega_kk (the curve's EDFs are optimistic at the
//      longest taus). R and nu ignore how the parametric terms change the estimates'
//      correlations and EDFs (the band-limit: at the shortest taus), which is second order where
//      they are small and is what the bootstrap option is for.
// Jacobian: analytic in the linear terms, central differences in the parametric parameters
// (ln scale); the residual functor passes Ceres' gradient check (tests). Uncertainties:
// (J' J)^{-1} of the whitened problem at the solution, mapped back to SI.
// Term selection (select_terms) is that of the linear fit (linear_profile.h): every subset of the
// linear terms scored by AIC on the cost's expansion at the fit of all terms, the parametric
// parameters free to first order; the choice refitted with the other terms held at zero, those
// reported by their 95 % upper limit, every term's ranges the hull over the competitive subsets.
// The parametric terms are always kept: the caller compares chi2 of nested fits for them (the
// band-limit detection, band_limited_fit.h; the diagnosis, docs/theory.md §6.4).
// With the band-limit, each term's AVAR is its own exact AVAR plus the band-limit's change
// (sim/band_limited_avar.h: exact for all but Kasdin flicker, whose start-up x band-limit product
// is left out), so the linear terms' own shapes are computed once and a new cutoff costs
// O(len(q)) per tau and term.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "estimators/fit/avar_curve.h"
#include "estimators/fit/fit_avar_model.h"
#include "estimators/fit/parametric_term.h"
#include "sim/sensor_model.h"

namespace allanlab::estimators {

struct ParametricFitOptions {
  FitMethod method = FitMethod::kGls;  // kWls, kLogWls or kGls (kSlope is not a fit)
  std::vector<Coefficient> terms = {Coefficient::kQ, Coefficient::kN, Coefficient::kB,
                                    Coefficient::kK, Coefficient::kR};
  std::vector<std::shared_ptr<const ParametricTerm>> extra;  // at most one band-limit
  int max_iterations = 200;  // Ceres iterations per stage
  // kBootstrap: every sigma from the spread of refits of curves simulated from the fitted model
  // (parametric_bootstrap.h); a replicate in which a parametric term could not be fitted counts
  // as failed. The harmonic amplitude needs it: its covariance sigma is several times too small.
  FitUncertainty uncertainty = FitUncertainty::kCovariance;
  BootstrapOptions bootstrap;
  // Optional, GLS: a covariance model of this curve built with every term of `terms`
  // (FitOptions::covariance); null: built when needed.
  std::shared_ptr<const AvarCovarianceModel> covariance;
  // Screening (band_limited_fit.h): when a parametric term has no starting point
  // (ParametricTerm::InitialGuess fails), stop before the pilot and final stages: the summary is
  // ok, that term is not fitted (its note says why) and base holds no fitted coefficients. The
  // caller that discards such fits anyway saves their cost (on a 1e7-sample record without a
  // band-limit, ~0.5 s of CPU for BW and BW2).
  bool stop_without_start = false;
  // Choose the linear terms by AIC (header); false: every listed term is fitted.
  bool select_terms = false;
  // false: no profile ranges of the linear terms (FitOptions::profile_ranges).
  bool profile_ranges = true;
  bool IsValid(std::string* why) const;
};

struct ParametricEstimate {
  std::string id;                 // ParametricTerm::id()
  std::string short_name;         // ParametricTerm::short_name()
  std::vector<ParameterSpec> parameters;
  std::vector<double> value_si;   // in parameters order
  std::vector<double> sigma_si;   // standard uncertainties (0 if not fitted)
  std::vector<double> covariance_sigma_si;  // the covariance sigmas (= sigma_si unless bootstrapped)
  std::vector<double> bootstrap_bias_si;    // mean of the replicates - value_si (bootstrap only)
  // The 95 % profile range of each parameter (a band-limit's cutoff: the fit's minimum over the
  // linear terms at other cutoffs, parametric_fit.cc); empty where not profiled. Where the curve
  // does not pin the cutoff the range is far wider than +- 1.96 sigma (a 131 Hz cutoff averaged
  // to a 100 Hz output: fc 74 +- 5 Hz, range up to the 360 Hz bound).
  std::vector<std::array<double, 2>> interval95_si;
  bool fitted = false;
  std::string note;               // why not fitted, or caveats (at a bound)
};

struct ParametricFitSummary {
  // Linear coefficients, chi2, dof (taus - all fitted parameters), p_value, converged, message.
  FitSummary base;
  std::vector<ParametricEstimate> extra;  // in options.extra order
  bool ok = false;                        // = base.ok
};

// Returns summary->ok; failures (invalid options or curve, too few taus, solver failure) give a
// message. Precondition for kGls: an overlapping curve with its record length.
bool FitAvarModelWithTerms(const ParametricFitOptions& options, const AvarCurve& curve,
                           ParametricFitSummary* summary);

// The fitted model as a sim::SensorModel at the curve's sample rate: the fitted linear terms and
// parametric terms (what the bootstrap simulates, what plots draw).
sim::SensorModel FittedModel(const ParametricFitOptions& options, const AvarCurve& curve,
                             const ParametricFitSummary& summary);

// Expected AVAR of a model on the curve's averaging factors and record (sim::SensorModel::ExpectedAvar with FlickerBandLimit::kStationaryChange).
std::vector<double> ModelAvarOnCurve(const sim::SensorModel& model, const AvarCurve& curve);

}  // namespace allanlab::estimators
