#pragma once
// The linear part of a fit as a non-negative least-squares problem, and what is read off it:
// which subset of terms the curve supports, and profile-likelihood intervals and upper limits.
//
// chi2(x) = |y - A x|^2 over x >= 0, x_j the j-th term's squared coefficient (scaled), A the
// whitened design. For WLS and GLS with the weights held at the fit's (GLS: Omega fixed at the
// pilot) this is the fit's own cost exactly; for log-WLS and for the linear terms of a parametric
// fit (the nonlinear parameters held at their fit) it is the Gauss-Newton expansion of the cost
// at the solution: y = r + A x_hat with r the whitened residuals and A = -dr/dx.
//
// Term selection: every subset of the terms is fitted (2^p small NNLS, 32 for Q,N,B,K,R) and
// scored by Akaike's criterion -2 log L + 2 (terms in the subset), L the Gaussian likelihood of
// the curve (LikelihoodCost: chi2 under W0 where the covariance does not depend on the model);
// the lowest score wins, ties to the smaller subset. Scoring all subsets cannot lose a term because another took its place first, as
// backward elimination did (with Q,N,B,K,R on 2 h of N + B + K the ramp R absorbed K, K went to
// the boundary and was dropped, then R too). AIC rather than a likelihood-ratio test at 5 %: the
// subsets are not nested in one chain, and AIC scores them all on one scale; between two nested
// subsets one term apart it keeps the term when chi2 falls by more than 2, a test at level
// 0.5 P(chi2_1 > 2) = 7.9 % under the null (the term's c^2 sits on the c^2 >= 0 boundary).
//
// Profile likelihood: the profile of x_j is min chi2 over the other free terms with x_j held; its
// rise above the minimum, Delta, gives the intervals. The 68.3 % and 95 % intervals accept a held
// value t when Delta(t) is below the critical value of the bounded likelihood ratio at t
// (bounded_threshold.h, Feldman & Cousins): the chi2_1 quantiles 1 and 3.841 far from the
// boundary, falling to 0.227 and 2.706 at x_j = 0; with GLS, where the estimate of x_j is skewed
// (K, R), a parametric bootstrap of the statistic sets it (profile_calibration.h). The fixed chi2_1 quantiles over-cover there
// (0.5 + 0.5 level at x_j = 0: 84 % at a nominal 68.3 %; bounded_threshold_stat_test.cc). A term the data do
// not determine also gets the one-sided 95 % upper limit at Delta = 2.706 (the 50:50 mixture of
// chi2_0 and chi2_1 puts 5 % above it). The interval of c = sqrt(x) is the square root of x's:
// no first-order propagation, which fails near the boundary.
#include <functional>
#include <vector>

#include <Eigen/Dense>

#include "estimators/fit/fit_avar_model.h"

namespace allanlab::estimators {

struct LinearProblem {
  Eigen::MatrixXd a;  // whitened design, one column per term
  Eigen::VectorXd y;  // whitened target
  double Chi2(const Eigen::VectorXd& x) const { return (y - a * x).squaredNorm(); }
  // Optional (GLS): the whitening W (W' W = Omega^-1) of the curve's covariance under the model
  // x, and the unwhitened design and target (a = W0 design, y = W0 target for the W0 the fit
  // held). When set, the profile tests each held value under the covariance of that value's
  // model (see ProfileInterval) instead of W0's. The fits wrap it in CachedWhitening
  // (whitening_cache.h): the score, the goodness of fit and the profile ask for the same x.
  std::function<bool(const Eigen::VectorXd& x, Eigen::MatrixXd* w)> whitening_at;
  Eigen::MatrixXd design;
  Eigen::VectorXd target;
  Eigen::MatrixXd whitening;  // W0: a = W0 design, y = W0 target
  // Optional, with whitening_at: unwhitened directions of parameters free to first order (the
  // curve's derivatives in a band-limit's cutoff, ...), projected out of the problem whitened at
  // each held value as a and y were projected out under W0.
  Eigen::MatrixXd free_directions;
  // Optional, with whitening_at: the part of the model's expected AVAR outside design x (the
  // additive parametric terms of a parametric fit), so that design x + offset is the expectation
  // and target + offset the curve; empty: none.
  Eigen::VectorXd offset;
};

// min |A x - y|^2 over x >= 0 (Lawson-Hanson active set on column-normalised A: exact for these
// small, badly scaled designs, where a bounded iterative solver stops short).
Eigen::VectorXd NonNegativeLeastSquares(const Eigen::MatrixXd& a, const Eigen::VectorXd& y);

// The NNLS solution with only the terms in `free_mask` (bit j: column j) free, the others 0.
Eigen::VectorXd SolveSubset(const LinearProblem& p, unsigned free_mask);

struct SubsetChoice {
  unsigned mask = 0;  // the terms kept
  Eigen::VectorXd x;  // their NNLS solution (0 outside the mask)
  double chi2 = 0.0;
  double score = 0.0;  // LikelihoodCost + 2 popcount(mask)
  // `mask` first, then every subset that is not a superset of it and scores within
  // kCompetitiveAic of it: the alternatives the data do not tell apart from the choice (Burnham &
  // Anderson's confidence set of models). Supersets are left out: one more term never costs more
  // than 2, so every superset would qualify while adding only a term the data did not ask for.
  // Except the choice plus one term that lowers chi2 by more than 2 - kSupportedTermAic = 1 (it
  // scores within kSupportedTermAic of the choice): a term the data support at one sigma though
  // AIC leaves it out. Without it, on 2 h of the rlg sensor AIC leaves out B (its floor barely
  // shows under the white noise), K takes the flicker's rise, and K's 95 % interval in {N, K}
  // missed the truth in 13 % of records (independent records, 150).
  std::vector<unsigned> competitive;
};
inline constexpr double kCompetitiveAic = 2.0;
inline constexpr double kSupportedTermAic = 1.0;
// Every subset of the columns, scored by AIC (header) on LikelihoodCost. Precondition:
// a.cols() <= 16.
SubsetChoice SelectSubsetByAic(const LinearProblem& p);

// -2 log of the Gaussian likelihood of the curve under the model x, up to a constant: with
// p.whitening_at, chi2 under the model's own covariance Omega(x) plus log det Omega(x) (relative
// to W0's); without, p.Chi2(x). Why not p.Chi2(x) under W0 alone: W0 is the covariance of a
// pilot fit, whose small K made the long taus' variances too small, so a subset that put a ramp R
// or a flicker floor B where K belonged scored best under W0 while its own covariance called it a
// poor fit: on 2 h records of white noise and a rate random walk from independent/ (10 Hz), AIC
// under W0 chose such a subset and the fit was called poor in 6 of 200 (8 of 160 with a flicker
// floor); scored on the likelihood, in 1 of 200 and 1 of 160 (profile_coverage_stat_test.cc,
// docs/theory.md §4.8).
// log det Omega(x) is what keeps a subset from explaining a misfit by inflating its own variance.
// x is each subset's fit under W0, not its maximum-likelihood fit: the score ranks subsets, it
// does not refit them. Infinite where whitening_at cannot form the covariance (x = 0 included);
// SelectSubsetByAic scores by W0 only when no subset's can be formed.
double LikelihoodCost(const LinearProblem& p, const Eigen::VectorXd& x);

// The interval levels, and the Delta chi2 of the chi2_1 ranges at those levels.
inline constexpr double kProfileLevel68 = 0.6826894921370859;  // +- 1 sigma of a Gaussian
inline constexpr double kProfileLevel95 = 0.95;
inline constexpr double kProfileDelta68 = 1.0;
inline constexpr double kProfileDelta95 = 3.841458820694124;
inline constexpr double kProfileDeltaUpper95 = 2.705543454095404;

struct ProfileRange {
  double lower = 0.0;  // x_j; 0 when the profile stays below the level down to x_j = 0
  double upper = 0.0;
};
// The x_j range where the profile of x_j (the terms of free_mask free, j included) stays within
// `delta` of its minimum. Precondition: bit j of free_mask set.
// With p.whitening_at set, the statistic at a held value t is the distance test of GMM
// (Newey & West 1987) with the weight that is efficient under that hypothesis: the covariance
// Omega_t of the model fitted with x_j = t under W0, then Delta(t) = min chi2_t(x_j = t) -
// min chi2_t, both with Omega_t. Holding W0 (the pilot's covariance) instead tests a large x_j
// against the small long-tau variances of a model with a small one: on 2 h records of
// N + B + K the 95 % upper limit of K then held the truth in 6 of 8 records. Each t is tested
// at its own level, so the range is the inverted test; Delta(t) need not be convex, and each end
// is the first crossing from the estimate outwards. An end the test never reaches (Delta stays
// below `delta` up to 1e12 times the estimate's scale) is +infinity.
ProfileRange ProfileInterval(const LinearProblem& p, unsigned free_mask, int j, double delta);
// The same with the critical value a function of the held value t.
ProfileRange ProfileInterval(const LinearProblem& p, unsigned free_mask, int j,
                             const std::function<double(double t)>& delta);
// The fit with x_j held at t and the other terms of free_mask free (NNLS under p's weights).
Eigen::VectorXd SolveHeld(const LinearProblem& p, unsigned free_mask, int j, double t);
// Delta(t), the statistic ProfileInterval compares with the critical value (above).
double ProfileStatistic(const LinearProblem& p, unsigned free_mask, int j, double t);
// One end of the range, the first crossing from the estimate outwards (lower: 0 when no held value
// from the estimate down to 0 is rejected), bisected
// to `relative_tolerance` of the end (0: 1e-6 with p.whitening_at set, else 1e-9). NaN when the
// estimate itself is rejected (delta below 0 there: an alternative problem too far above the fit).
double ProfileEnd(const LinearProblem& p, unsigned free_mask, int j,
                  const std::function<double(double t)>& delta, bool upper, double relative_tolerance = 0.0);
// The `level` interval with the bounded critical value (header): t is accepted when Delta(t) +
// offset <= BoundedLikelihoodRatioThreshold(level, t / sigma_j), sigma_j the standard error of
// x_j among the free terms (from A, unconstrained). offset: how far p's minimum lies above the
// fit's (an alternative problem of SetProfileRanges); both ends NaN when the estimate itself is
// then rejected.
ProfileRange BoundedProfileInterval(const LinearProblem& p, unsigned free_mask, int j, double level,
                                    double offset = 0.0);
// sigma_j above: the standard error of x_j with the terms of free_mask free (unconstrained).
double ProfileStandardError(const LinearProblem& p, unsigned free_mask, int j);
// The whitened design's columns of the free terms (free_mask), in order, and *at_j the position of
// term j among them.
Eigen::MatrixXd FreeColumns(const LinearProblem& p, unsigned free_mask, int j, Eigen::Index* at_j);

// Alternative problems: the same columns with a nonlinear parameter of the fit held at other
// values (a band-limit's cutoff: CutoffAlternatives of parametric_fit.cc), which p lets move only
// to first order. Where the curve does not pin that parameter, a term it trades with is pinned
// only by the cutoff held at the fit's value: on a 1 h record of the tactical_mems sensor at
// 100 Hz (a 131 Hz low-pass averaged to the output) the fit chose fc 72.7 Hz with Q 0.88 urad,
// 95 % [0.66, 1.01], while fc 134 Hz with Q = 0 lay only 1.07 above it in chi2. The profile over
// both is the minimum over the alternatives of each one's statistic plus its offset (its minimum's
// chi2 above p's, under the weight both hold): the union of each alternative's ranges at the
// critical value less its offset.
// The estimate's profile ranges in SI (c_j^2 = scale x_j): its 68.3 % and 95 % intervals
// (BoundedProfileInterval; with p.whitening_at set, CalibratedProfileIntervals of
// profile_calibration.h) and, when it is not fitted, its 95 % upper limit, each the hull of the
// ranges profiled in every subset of `free_masks` (column j added to those without it, whose
// intervals then start at 0). One mask: the ranges of that model. The competitive subsets of the
// AIC choice: ranges that hold what a different, equally supported choice would have given. An
// interval conditional on the subset the same data chose under-covers: on white noise AIC adds a
// spurious Q to 7 % of records, and N, traded against Q, then sits 3 sigma low (N's 68.3 %
// interval held the truth in 62 % of 2 h records).
// With `alternatives`, the union above, over the alternatives whose estimate of x_j differs from
// p's by more than kTradeShift of its standard error: the ranges of a term that does not trade
// with the parameter they move stay where p's are, and each alternative's ranges cost as much as
// p's (on that record the fit took 0.7 s with none, 3.7 s with all).
inline constexpr double kTradeShift = 0.2;
void SetProfileRanges(const LinearProblem& p, const std::vector<unsigned>& free_masks, int j,
                      double scale, CoefficientEstimate* e, const std::vector<LinearProblem>& alternatives = {});

// The problem whitened by the covariance of the model x (p.whitening_at), with p.free_directions
// projected out: what ProfileStatistic tests a held value under. False (q untouched) when
// p.whitening_at is unset or fails.
bool WhitenedAt(const LinearProblem& p, const Eigen::VectorXd& x, LinearProblem* q);

// The goodness of fit of the subset `mask` (GLS, p.whitening_at set): the subset refitted under
// the covariance Omega of its fit, and the curve's departure from that model's expectation mu
// measured with chi-square marginals in a Gaussian copula: each estimate's z from its ratio to mu
// on nu_k = 2 mu_k^2 / Omega_kk degrees of freedom (Wilson-Hilferty), correlated as Omega says.
// Gaussian residuals under Omega (chi2 = r' Omega^-1 r) make a curve 5x below its model at the
// long taus, where nu is ~10, a 1.8 sigma event where chi-square gives 2.7: the MTi-G record's
// IEEE fit (B 46 deg/h over a 6 deg/h floor) then passed at p = 0.004. Returns false (chi2
// untouched) where the covariance cannot be formed.
bool GoodnessOfFitChi2(const LinearProblem& p, unsigned mask, double* chi2);

// The profile ranges of every term of a fit: SetProfileRanges for each column j of p into
// summary->coefficients[terms[j]] (c^2 = scale[j] x_j), over the subsets `free_masks`. The one
// place where a fit's profile chooses its weight, for the linear fit and the parametric one alike:
// each held value's own covariance (p.whitening_at) where the model describes the curve; the
// weight the fit held (W0) where it does not, judged by IsPoorFit on the summary's goodness of fit
// (JudgeGoodnessOfFit below, called first). Where the model does
// not describe the curve the misfit, not the noise, sets chi2 under every covariance, the minimum
// under each held value's covariance moves with it, and the held-value test collapsed N's interval
// to its value (ADIS16405 Gyro_Z, chi2 4.3e5 on 50 dof; docs/theory.md §4.7). The fit's own chi2
// (under W0) does not tell the two apart: on 2 h records of white noise and a rate random walk,
// 25 of 200 had p < 1e-3 under the pilot's weight, whose small K made the long taus' variances
// too small, and the fallback moved K's 95 % coverage there from 191 to 177 of 200.
// `alternatives`: as SetProfileRanges (the same weight rule applies to them).
void SetFitProfileRanges(LinearProblem p, const std::vector<unsigned>& free_masks, const std::vector<int>& terms,
                         const std::vector<double>& scale, FitSummary* summary,
                         std::vector<LinearProblem> alternatives = {});

// The fit's goodness of fit (FitSummary::gof_chi2, gof_p_value): GoodnessOfFitChi2 of the chosen
// subset free_masks.front() (every term when empty) on summary->dof, where p.whitening_at is set
// (GLS); otherwise the summary keeps its cost. Every linear and parametric fit calls it, with or
// without profile ranges.
void JudgeGoodnessOfFit(const LinearProblem& p, const std::vector<unsigned>& free_masks, FitSummary* summary);

}  // namespace allanlab::estimators
