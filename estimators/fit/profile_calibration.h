#pragma once
// Critical values of the profile statistic calibrated by a parametric bootstrap of the Allan
// curve, for the GLS fit's profile intervals (docs/theory.md §4.8).
//
// The bounded likelihood-ratio threshold (bounded_threshold.h) assumes the curve's estimates are
// Gaussian. The long-tau estimates that alone pin K (and R) are chi-square-like with a few
// degrees of freedom: most fall below their mean and a few far above it. On 400 independent
// 2 h records whose K is far below what they resolve (N, B and K of the mg25_mems sensor, 10 Hz,
// seeds 1-400) K's estimate was at 0 in 56 % and the statistic at the true K had its 68.3 %
// quantile at 0.03 (Gaussian 0.227) and its 95 % one at 1.97 (Gaussian 2.706): K's 68.3 %
// interval held the truth in 81 % of records.
//
// The null distribution of Delta(t) is simulated under the model held at t: theta_t (the fit with
// x_j = t), its covariance Omega_t (p.whitening_at), and replicate curves whose estimates have the
// Gaussian copula of Omega_t and chi-square marginals, E_i chi2_nu / nu with nu_i = 2 E_i^2 /
// Omega_t,ii (the Wilson-Hilferty cube of the Gaussian deviate: the same mean and variance, and
// the chi-square's skew). Each replicate is refitted with Omega_t held. The same deviates with
// Gaussian marginals give the reference, and the critical value is the Gaussian (bounded) one
// times the ratio of the two quantiles: the skew's effect alone, where the replicates' own
// quantile would also carry the held Omega_t's inflation of the upper tail.
//
// Where it is computed. Each calibration is a set of kCalibrationReplicates replicates at one held
// value t, from which both levels' ratios are read. The ratio rises with t, from near 0 at the
// boundary (K's statistic there is mostly 0) to 1 far from it, and the ends move with it, so an
// end is found by iterating: search it with the ratio interpolated linearly in t between the
// values calibrated so far (held beyond the first and the last; none: the Gaussian end), calibrate
// at the end found, and stop when a calibrated value lies within kEndTolerance of it (at most
// kMaxCalibrations per end); a lower end first calibrates t = 0, where the ratio is smallest.
// Typically 2-6 calibrations per term and subset, where evaluating it at every t the search
// visited took about 20 times the fit's time on short records. Calibrated only where the estimate
// is skewed and the Gaussian 68.3 % range reaches 0: away from the boundary the ratio stays within
// the replicates' noise of 1 at 68.3 % (0.96-1.1 on the records above).
#include "estimators/fit/linear_profile.h"

namespace allanlab::estimators {

inline constexpr int kCalibrationReplicates = 200;
inline constexpr double kGaussianSkewness = 0.1;
inline constexpr double kEndTolerance = 0.05;  // relative
inline constexpr int kMaxCalibrations = 4;      // per end

// Skewness of the estimate of x_j (a linear combination of the curve's estimates, each treated
// as chi-square-like with the variance of p.whitening's covariance, correlations ignored): below
// kGaussianSkewness the Gaussian threshold is used as it is.
double EstimateSkewness(const LinearProblem& p, unsigned free_mask, int j);

// The ratio of the replicates' quantiles (chi-square marginals over Gaussian ones) of Delta(t)
// at the 68.3 % and the 95 % level, from the same replicates (fixed seed: the same deviates at
// every t). {1, 1} when the covariance at t cannot be formed; 1 at a level whose reference
// quantile is 0. Preconditions: bit j of free_mask set, t >= 0.
struct CalibrationRatio {
  double at68 = 1.0;
  double at95 = 1.0;
};
CalibrationRatio CalibrationRatioAt(const LinearProblem& p, unsigned free_mask, int j, double t);

struct ProfileRanges {
  ProfileRange at68;
  ProfileRange at95;
};
// The 68.3 % and 95 % ranges of x_j: BoundedProfileInterval when p.whitening_at is unset, the
// estimate of x_j is nearly Gaussian (|EstimateSkewness| < kGaussianSkewness: N, Q and mostly B)
// or the Gaussian 68.3 % range stays off 0; else t is accepted when Delta(t) <= the bounded
// threshold times the interpolated ratio (header), each end to kEndTolerance. offset: subtracted
// from every critical value (an alternative problem whose minimum lies that far above the fit's,
// linear_profile.h); a range whose estimate it rejects has NaN ends.
ProfileRanges CalibratedProfileIntervals(const LinearProblem& p, unsigned free_mask, int j, double offset = 0.0);

}  // namespace allanlab::estimators
