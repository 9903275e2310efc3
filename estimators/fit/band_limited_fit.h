#pragma once
// What `allanlab fit` does by default when the sensor is band-limited (most are: ~100 Hz for the
// MEMS gyros of the seed paper). The IEEE 952 shapes (Q, N, B, K, R) know no band-limit, and the
// short taus, whose EDFs are the largest, then dominate a WLS/GLS cost: on a 1 h, 400 Hz record
// of the mg25_mems preset GLS gave B = 1.9 deg/h (true 0.18) with chi2 = 5e4 on 54 dof.
//
// Policy (kAuto): fit the band-limit instead of cutting the taus away, so the short taus inform
// N and Q and the cutoff is measured:
//   1. the plain fit (FitAvarModel, with its term selection);
//   2. the same terms plus a band-limit term, once with a first-order low-pass (BW) and once with
//      a 2nd-order Butterworth (BW2), by FitAvarModelWithTerms (exact band-limited shapes,
//      sim/band_limited_avar.h); the lower chi2 of the two wins (same parameter count);
//   3. the band-limited fit is reported when it lowers chi2 by more than the chi2 quantile at
//      `detection_level` for the extra parameters it uses (the cutoff, and the terms the plain
//      fit's selection dropped), and its cutoff is not at a bound; otherwise the plain fit.
// The chi2 of the two fits come from different pilot weights (fit_avar_model.h), so the test is a
// screening rule, not an exact likelihood-ratio test; detection_level is small to keep it from
// firing on curves without a band-limit. The candidates keep every term; the reported
// band-limited fit then chooses its terms as the plain fit does when the options ask it
// (parametric_fit.h): a term the data do not support is left out and reported by its 95 %
// profile upper limit, never as a point with an interval.
// The chain assumed (averaged or point-sampled output, oversampling L) is an option: averaging
// keeps N the long-tau white level (parametric_term.h); the seed presets average with L = 8.
// With FitUncertainty::kBootstrap the candidates are compared on covariance fits and only the
// reported one is bootstrapped.
#include <string>
#include <vector>

#include "estimators/fit/avar_curve.h"
#include "estimators/fit/fit_avar_model.h"
#include "estimators/fit/parametric_fit.h"

namespace allanlab::estimators {

enum class BandLimitPolicy {
  kOff,   // the plain fit only
  kAuto,  // detect and fit (above)
};

struct BandLimitedFitOptions {
  FitOptions fit;  // method (wls, logwls or gls; slope is never band-limited), terms, selection
  BandLimitPolicy policy = BandLimitPolicy::kAuto;
  sim::OutputSampling sampling = sim::OutputSampling::kAverage;  // of the assumed chain
  int oversampling = 8;                                           // L of the assumed chain, [1, 256]
  double detection_level = 1e-3;  // false-detection rate of the chi2 screening
  bool IsValid(std::string* why) const;
};

struct BandLimitedFitSummary {
  // The reported fit. summary.band_limit says what was done and why; tau_min_s / tau_max_s the
  // taus fitted.
  FitSummary fit;
  bool band_limited = false;                  // the reported fit includes the band-limit
  ParametricFitOptions parametric;            // its options (FittedModel), when band_limited
  std::vector<ParametricEstimate> extra;      // its band-limit estimate (fc), when band_limited
  double plain_chi2 = 0.0;                    // chi2 of the plain fit
  int plain_dof = 0;
  double band_limited_chi2 = 0.0;             // best band-limited fit tried (0 if none)
  int band_limited_dof = 0;
  bool ok = false;
};

// Returns summary->ok (= summary->fit.ok); on failure summary->fit.message says why.
bool FitWithBandLimit(const BandLimitedFitOptions& options, const AvarCurve& curve,
                      BandLimitedFitSummary* summary);

}  // namespace allanlab::estimators
