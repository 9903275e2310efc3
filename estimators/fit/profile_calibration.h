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
// Here the null distribution of Delta(t) is simulated under the model held at t: theta_t (the
// fit with x_j = t), its covariance Omega_t (p.whitening_at), and replicate curves whose
// estimates have the Gaussian copula of Omega_t and chi-square marginals, E_i chi2_nu / nu with
// nu_i = 2 E_i^2 / Omega_t,ii (the Wilson-Hilferty cube of the Gaussian deviate: the same mean and
// variance, and the chi-square's skew). Each replicate is refitted with Omega_t held, and the
// critical value is the `level` quantile of the replicates' Delta(t). With every nu large this is
// the Gaussian threshold again. The replicates draw the same deviates at every t (a fixed seed),
// so the threshold is smooth in t and the result is deterministic. On the records above it puts
// the 68.3 % value at 0.03-0.05 (median 0.037), as measured; its 95 % value, 3.2, is above the
// measured 1.97 (the held Omega_t does not follow a replicate as the fit's own covariance follows
// the data), so the 95 % intervals of K stay conservative there.
#include "estimators/fit/linear_profile.h"

namespace allanlab::estimators {

inline constexpr int kCalibrationReplicates = 400;
inline constexpr double kGaussianSkewness = 0.1;

// Skewness of the estimate of x_j (a linear combination of the curve's estimates, each treated
// as chi-square-like with the variance of p.whitening's covariance, correlations ignored): below
// kGaussianSkewness the Gaussian threshold is used as it is.
double EstimateSkewness(const LinearProblem& p, unsigned free_mask, int j);

// Preconditions: p.whitening_at set; bit j of free_mask set; 0 < level < 1; t >= 0. Returns the
// Gaussian threshold when the covariance at t cannot be formed.
double CalibratedCriticalValue(const LinearProblem& p, unsigned free_mask, int j, double t, double level);

// The `level` range of x_j: BoundedProfileInterval when the estimate of x_j is nearly Gaussian
// (|EstimateSkewness| < kGaussianSkewness: N, Q and mostly B), else t is accepted when Delta(t)
// <= CalibratedCriticalValue(t): the upper end widened from the Gaussian one until rejected, then
// bisected; the lower end 0 when 0 is accepted, else bisected below the estimate; both to 1 % of
// the end (in x_j, 0.5 % in the coefficient).
ProfileRange CalibratedProfileInterval(const LinearProblem& p, unsigned free_mask, int j, double level);

}  // namespace allanlab::estimators
