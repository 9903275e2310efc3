#pragma once
// The change-point statistic when the model's rate random walk K was fitted to the same record
// (docs/theory.md §6.7). A free K absorbs a step: the jump raises the long taus of the Allan curve
// the way a random walk does, the fitted K² grows, and against that inflated covariance the jump
// looks ordinary. And a fit that leaves K out judges a random walk's wander as steps. Here K² is
// a nuisance parameter of the block-mean differences' own Gaussian likelihood, profiled out under
// both hypotheses between 0 and kappa_max, the square of the largest K the fit allows (its 95 %
// upper end or upper limit; the random walk the record cannot exclude): with d ~ N(beta h, C0 +
// kappa Ck), C0 the model's
// covariance without its random walk and Ck that of a unit one,
//   T_h = min_kappa -2 ln L(kappa, 0) - min_{kappa, beta} -2 ln L(kappa, beta),
// so a step is judged against the random walk the other differences allow, not the one the step
// itself inflated. With Ck V = C0 V Lambda (V^T C0 V = I), y = V^T d and g = V^T h,
//   -2 ln L = sum_i ln(1 + kappa lambda_i) + (y_i - beta g_i)² / (1 + kappa lambda_i) + const,
// minimised over beta in closed form and over kappa in [0, kappa_max] on a log grid (26 % steps
// down from kappa_max) and 0. The maximum over the regressors has its own law under the model
// at the largest random walk allowed (kappa = kappa_max: y ~ N(0, I + kappa_max Lambda)), drawn by
// Monte Carlo with fixed seeds; the law of the statistic with K held does not serve (on controls
// with K 10 deg/h/sqrt(h) judged against their true model the profiled maximum exceeded it: 6.0 %
// false alarms against 3.5 %), nor its law at the fitted K when the fit left K out (9.5 % on
// controls with K 10; at kappa_max 2.0 %: docs/theory.md §6.7).
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace allanlab::experiments {

struct ProfiledStep {
  double t = 0.0;     // the likelihood-ratio statistic (~ chi2_1 under the model)
  double size = 0.0;  // beta at the profiled kappa [rad/s]
  double sd = 0.0;    // its standard deviation there [rad/s]
};

// A regressor in d-space, sparse: (index, value) pairs.
using SparseRegressor = std::vector<std::pair<std::size_t, double>>;

// T_h for each regressor, and `null_draws` draws of max_h T_h under the model (stream
// `null_stream` of a fixed seed); false (outputs untouched) when C0 is not positive definite or
// kappa_max ((rad/s)²/s) is not > 0. c0 and c_unit_rrw are the first rows of the
// Toeplitz covariances, d the block-mean differences, all of one length.
bool ProfileSteps(const std::vector<double>& c0, const std::vector<double>& c_unit_rrw, double kappa_max,
                  const std::vector<double>& d, const std::vector<SparseRegressor>& regressors, int null_draws,
                  std::uint64_t null_stream, std::vector<ProfiledStep>* out, std::vector<double>* null_maxima);

}  // namespace allanlab::experiments
