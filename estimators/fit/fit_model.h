#pragma once
// The one entry point of coefficient extraction from an Allan curve: the options list the terms
// (the IEEE 952 Q, N, B, K, R and the parametric GM, H, RTS, BW, BW2 of parametric_term.h), the
// method, term selection, the band-limit policy and the uncertainty; the summary holds every
// fitted coefficient and parameter, the fit's chi2 and what was decided on the way. `allanlab fit`
// makes this one call.
//
// Routes (each documented in its own header, all on the same residual and weight definitions):
//   * no parametric term, band_limit kOff: the linear fit (fit_avar_model.h), with term
//     selection when asked;
//   * no parametric term, band_limit kAuto: that fit and, when the short taus show a band-limit,
//     the same terms plus BW or BW2 (band_limited_fit.h decides and says why);
//   * parametric terms listed: one joint fit of them with the linear terms (parametric_fit.h),
//     every parametric term kept (they have no nested NNLS to select by), the linear terms
//     chosen as in the linear fit when select_terms is set (the extended models tried on a poor
//     fit too).
// FitAvarModel, FitWithBandLimit and FitAvarModelWithTerms stay public: they are the routes above,
// and the sim-to-real diagnosis calls them stage by stage.
#include <memory>
#include <string>
#include <vector>

#include "estimators/fit/avar_curve.h"
#include "estimators/fit/band_limited_fit.h"
#include "estimators/fit/fit_avar_model.h"
#include "estimators/fit/parametric_fit.h"
#include "estimators/fit/parametric_term.h"
#include "sim/sensor_model.h"

namespace allanlab::estimators {

struct ModelFitOptions {
  FitMethod method = FitMethod::kGls;
  std::vector<Coefficient> terms = {Coefficient::kQ, Coefficient::kN, Coefficient::kB,
                                    Coefficient::kK, Coefficient::kR};
  // Parametric terms fitted jointly with `terms` (at most one band-limit). Non-empty: every one
  // of them kept, no band-limit detection (a BW/BW2 listed here is the band-limit).
  std::vector<std::shared_ptr<const ParametricTerm>> extra;
  // Band-limit detection when `extra` is empty (band_limited_fit.h).
  BandLimitPolicy band_limit = BandLimitPolicy::kOff;
  sim::OutputSampling bw_sampling = sim::OutputSampling::kAverage;
  int bw_oversampling = 8;
  double bw_detection_level = 1e-3;
  bool select_terms = true;  // every subset of `terms` scored by AIC (fit_avar_model.h, linear_profile.h)
  FitUncertainty uncertainty = FitUncertainty::kCovariance;
  BootstrapOptions bootstrap;
  // Optional, GLS: the covariance model of this curve built with every term of `terms`.
  std::shared_ptr<const AvarCovarianceModel> covariance;
  // On a poor fit without parametric terms: also fit the terms with each of GM, H, BW and BW2
  // (RTS has GM's Allan variance, so it is not tried apart; the band-limit found, if any, kept)
  // and report the best by AIC in ModelFitSummary::extended, if its AIC is below the fit's own;
  // when it fits, it becomes the reported fit (poor_fit stays true: it is about the terms alone).
  bool try_extended_on_poor_fit = false;
  // GLS: also fit by log-WLS (same terms, same selection) and name the coefficients where the
  // two differ by more than 3 GLS sigmas, in ModelFitSummary::method_disagreement.
  bool cross_check_log_wls = false;
  bool IsValid(std::string* why) const;
};

// A fit with parametric terms tried because the linear terms alone fit poorly.
struct ExtendedFit {
  std::string name;  // "GM", "H", "BW", "BW2" (with "+BW"/"+BW2" when the band-limit was kept)
  FitSummary fit;
  std::vector<std::shared_ptr<const ParametricTerm>> extra_terms;
  std::vector<ParametricEstimate> extra;
  double aic = 0.0;   // chi2 + 2 (fitted parameters)
  bool fits = false;  // not a poor fit (IsPoorFit, fit_avar_model.h)
};

struct ModelFitSummary {
  // The linear coefficients, chi2, dof, p_value, taus used, band-limit decision, message.
  FitSummary fit;
  // The parametric terms fitted (those listed, or the band-limit the detection kept) and their
  // estimates, in the same order.
  std::vector<std::shared_ptr<const ParametricTerm>> extra_terms;
  std::vector<ParametricEstimate> extra;
  bool band_limited = false;  // the reported fit includes a band-limit the detection found
  double plain_chi2 = 0.0;    // band-limit detection: chi2 and dof of the fit without it
  int plain_dof = 0;
  bool poor_fit = false;      // the fit of the listed terms is poor (IsPoorFit)
  double poor_chi2 = 0.0;     // poor fit: that fit's chi2 and dof
  int poor_dof = 0;
  // try_extended_on_poor_fit: every extended model tried (failed fits left out), and the index
  // of the best by AIC (-1: none lowers the AIC of the fit of the listed terms).
  std::vector<ExtendedFit> extended;
  int best_extended = -1;
  // cross_check_log_wls: "" or e.g. "N: GLS 2.956, log-WLS 2.485 (4.8 sigma)" per coefficient.
  std::string method_disagreement;
  bool ok = false;
};

// Returns summary->ok; on failure summary->fit.message says why.
bool FitModel(const ModelFitOptions& options, const AvarCurve& curve, ModelFitSummary* summary);

// The fitted model (linear and parametric terms) at the curve's sample rate: what the plots draw
// and a bootstrap simulates.
sim::SensorModel FittedModel(const AvarCurve& curve, const ModelFitSummary& summary);

}  // namespace allanlab::estimators
