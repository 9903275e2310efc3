#pragma once
// One coefficient-recovery trial, shared by the `coefficient_recovery` and `record_length`
// validation tables: simulate the point's record, take its overlapping Allan curve on
// the spec's tau grid, fit it with every method of the spec (slope, wls, log_wls, gls) and compare
// each coefficient present in the truth with its true value.
//
// Choices fixed here (each report states them):
//  * Fit taus: only taus where the point's band-limit lowers the white-noise AVAR by at most
//    kMaxBandLimitDeficit, and by at most kMaxBandLimitDeficitInSd of the relative standard
//    deviation sqrt(4m / 3N) of an overlapping white-noise estimate there (EDF ~ 1.5 N/m,
//    docs/theory.md §3.2; the deficit from the exact discrete theory of the model's filter, §2.9).
//    No fit term knows the band-limit, so shorter taus bias N low at every record length (GLS
//    on all octave taus of mg25_mems at 100 Hz: N 5 % low). A fixed deficit is not enough: the
//    bias it leaves is fixed while the scatter falls as 1/sqrt(N), so on 24 h of the fog preset
//    at 125 Hz the 0.5 % cut (m = 4, deficit 0.32 % there and ~1/m beyond) biased N by -0.13 %
//    (GLS; WLS -0.10 %) = 3.9 of its sigmas, and the 68 % intervals covered 0 of 16 trials. The
//    fit of the exact expected curve reproduces that bias and shows it halves with each octave
//    dropped; at deficit <= sd / 4 it stays below ~0.2 sigma. Every method gets the same curve.
//  * A spec with fit.tau_range fixes the fitted taus instead: the same window at every point (so
//    a sweep of the record length changes only how many clusters each tau has). The window must
//    satisfy the band-limit rule above at every point, and its longest tau must leave >= 8
//    clusters; a spec that breaks either is rejected (std::invalid_argument) before any trial.
//  * The slope method reads the same curve cut at m <= N / kSlopeMethodMaxFraction, the
//    plotted diagram a practitioner reads (the fits weigh the last, EDF ~ 1, taus themselves).
//  * Terms fitted: spec.fit_terms, or the truth's terms when it is empty; no term selection
//    (the question is how well a method recovers a known model, not which model it picks).
//  * A coefficient a fit leaves at zero is the estimate 0 with sigma 0 (relative error -1, not
//    covered); a failed fit, or a slope region the slope method does not find, is "missing".
//  * Method "default": `allanlab fit`'s defaults (estimators/fit/fit_model.h: GLS on Q,N,B,K,R
//    with the AIC subset choice, whatever spec.fit_terms says; those only name the compared
//    coefficients) on the same curve; in_ci<L> is whether the truth lies in its profile-likelihood
//    interval of that level (68.3 % or 95 %; a term the fit leaves out has the interval from 0).
//
// Columns, per method M (spec.fit_methods, in order) and coefficient C (fitted and in the truth):
//   rel_err/M/C         estimate / truth - 1                      mean: relative bias
//   sq_rel_err/M/C      (estimate / truth - 1)^2                  mean: relative MSE (RMSE^2)
//   missing/M/C         1 when there is no estimate               mean: failure rate
//   rel_sigma/M/C       reported sigma / truth (fits only)        mean vs std of rel_err
//   in_ci<L>/M/C        |estimate - truth| <= z_L sigma (fits)    mean: coverage of level L
// where L is each spec confidence level in percent ("in_ci68.3", "in_ci95") and z_L the normal
// quantile. For the slope method's B, when N and K are in the truth, also rel_err_read/slope/B
// and sq_rel_err_read/slope/B against what the curve minimum estimates, sqrt(B^2 + 2.617 N K)
// (docs/theory.md §4.2). Per fit method also failed/M (the fit returned !ok) and converged/M.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "estimators/fit/noise_coefficient.h"
#include "experiments/injected_fault.h"
#include "experiments/trial_driver.h"
#include "sim/sensor_model.h"

namespace allanlab::experiments {

// Largest white-noise AVAR deficit of the band-limit a fitted tau may have, absolute and as a
// share of the relative standard deviation of the estimate at that tau.
inline constexpr double kMaxBandLimitDeficit = 0.005;
inline constexpr double kMaxBandLimitDeficitInSd = 0.25;
// The slope method's curve ends at m = N / kSlopeMethodMaxFraction.
inline constexpr std::int64_t kSlopeMethodMaxFraction = 8;

// The IEEE 952 coefficients of a model, in SI, from its quantization, white rate, Kasdin
// flicker, random-walk and ramp terms (several terms of one kind add in quadrature). Other
// terms (Gauss-Markov, harmonics, ...) have no coefficient and are listed in `unmapped`.
struct TrueCoefficients {
  std::array<double, 5> value_si = {};
  std::array<bool, 5> present = {};
  std::vector<std::string> unmapped;
  double at(estimators::Coefficient c) const { return value_si[static_cast<int>(c)]; }
  bool has(estimators::Coefficient c) const { return present[static_cast<int>(c)]; }
};
TrueCoefficients TrueCoefficientsOf(const sim::SensorModel& model);

// What B from the curve minimum estimates with N, B, K present: sqrt(B^2 + 2.617 N K) (SI).
double SlopeMethodBTarget(const TrueCoefficients& truth);

// Smallest averaging factor among `candidates` (ascending) whose white-noise AVAR deficit under
// the model's band-limit is at most min(kMaxBandLimitDeficit, kMaxBandLimitDeficitInSd
// sqrt(4m / 3 num_samples)) on the model's sample clock; 1 without a band-limit.
std::int64_t SmallestFitAveragingFactor(const sim::SensorModel& model, std::int64_t num_samples,
                                        const std::vector<std::int64_t>& candidates);

// The averaging factors the fits of a point use: [min_m, max_m] (max_m: the grid's last one
// when the spec fixes no tau range). Throws std::invalid_argument on a bad grid or a fixed range
// the point cannot honour (see above).
struct FitAveragingWindow {
  std::int64_t min_m = 1;
  std::int64_t max_m = 0;
};
FitAveragingWindow FitWindowOf(const SweepSpec& spec, const SweepPoint& point);

// The method names the spec may list, in table order.
inline constexpr const char* kFitMethodNames[] = {"slope", "wls", "log_wls", "gls"};  // "default" on request
// Methods of a spec (all four when it lists none) and the coefficients compared at a point.
std::vector<std::string> MethodsOf(const SweepSpec& spec);

// The coverage column's stem for a confidence level: 0.683 -> "in_ci68.3", 0.95 -> "in_ci95".
std::string CoverageColumnName(double level);
std::vector<estimators::Coefficient> ComparedCoefficients(const SweepSpec& spec,
                                                          const SweepPoint& point);

class CoefficientTrialDriver : public FaultInjectableDriver {
 public:
  using FaultInjectableDriver::FaultInjectableDriver;
  std::vector<std::string> Columns(const SweepSpec& spec, const SweepPoint& point) const override;
  std::unique_ptr<TrialWorkspace> MakeWorkspace() const override;
  std::vector<double> Run(const SweepSpec& spec, const SweepPoint& point, std::int64_t trial,
                          TrialWorkspace* workspace) const override;
};

}  // namespace allanlab::experiments
