#pragma once
// The baseline a diagnosis measures the record against: a held part (what the user's sensor model
// fixes: band-limit, quantizers, terms, coefficients) plus linear IEEE 952 terms fitted to the
// record's overlapping Allan curve with it (GLS, WLS when GLS fails or degenerates).
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "estimators/fit/avar_curve.h"
#include "estimators/fit/fit_avar_model.h"
#include "estimators/fit/parametric_term.h"
#include "experiments/diagnosis/curve_covariances.h"
#include "experiments/diagnosis/diagnose.h"
#include "sim/sensor_model.h"

namespace allanlab::experiments::detail {

// The curve a record or a table gives: fewer taus than this cannot carry a baseline and a
// candidate.
inline constexpr std::size_t kMinTaus = 8;

// What is fitted and what is held.
struct BaselineSpec {
  std::vector<estimators::Coefficient> terms;  // fitted (empty: the held part alone)
  sim::SensorModel held;  // band-limit, quantizers and terms held as given (empty: a plain fit)
  // The GLS covariance models every fit with this spec shares (null: each fit builds its own).
  std::shared_ptr<CurveCovariances> covariances;
  bool HoldsAnything() const;
  // The shared GLS covariance model of curves shaped like `curve` with `terms` (null without
  // `covariances` or terms).
  std::shared_ptr<const estimators::AvarCovarianceModel> Covariance(const estimators::AvarCurve& curve) const;
  // The held part plus the fitted linear terms (those with a positive value) on `sample_clock`.
  sim::SensorModel Model(const estimators::FitSummary& fit, SampleClock sample_clock) const;
  // The held band-limit as a fit-library term without free parameters (it filters the fitted
  // terms); nullptr when none is held.
  std::shared_ptr<const estimators::ParametricTerm> HeldBandLimitTerm() const;
  // The curve less the held terms' and quantizers' exact expected AVAR (band-limited), floored at
  // a tenth of the curve: what the fitted terms (and a candidate's effects) are fitted to. The
  // held additive part is subtracted rather than passed to the fit library as a term without
  // parameters: next to a band-limit such a term left the fit far from the generating model
  // (tactical_mems with B and K held, N refitted: N 3 % high, chi2 1345 on 45 dof against 53).
  estimators::AvarCurve WithoutHeldAdditive(const estimators::AvarCurve& curve) const;
};

// The spec's terms fitted to `curve` with its held part; false when neither GLS nor WLS fits. A
// WLS fallback is named in *note (may be null). No terms to fit: *fit asks for none.
// profile_ranges false: the coefficients' intervals and upper limits are left unset (the values
// and sigmas are the same), for a fit of which only the values are read.
bool FitLinear(const BaselineSpec& spec, const estimators::AvarCurve& curve,
               estimators::FitSummary* fit, std::string* note, bool profile_ranges = true);

// The largest rate random walk K the fit allows when the spec fits K [rad/s/sqrt(s)]: the upper end
// of its 95 % interval, or its 95 % upper limit when the fit left K out (at least the fitted
// value); 0 when K is held (not among the spec's terms). What the change-point view profiles K
// over (block_means.h, docs/theory.md §6.7).
double RandomWalkBound(const BaselineSpec& spec, const estimators::FitSummary& fit);

// The whole record's baseline as the options ask (DiagnoseOptions::baseline): the spec later
// refits use, and the fit. False with *why on a failed fit or a sensor model that does not suit
// the record's rate; *note names a fallback or the band-limit found (may be empty).
bool FitBaseline(const DiagnoseOptions& options, const estimators::AvarCurve& curve,
                 BaselineSpec* spec, estimators::FitSummary* fit, std::string* note, std::string* why);

}  // namespace allanlab::experiments::detail
