#include "estimators/fit/linear_profile.h"

#include "estimators/fit/bounded_threshold.h"
#include "estimators/fit/profile_calibration.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <vector>

namespace allanlab::estimators {

Eigen::VectorXd NonNegativeLeastSquares(const Eigen::MatrixXd& a, const Eigen::VectorXd& y) {
  const Eigen::Index n = a.cols();
  Eigen::VectorXd norm(n);
  for (Eigen::Index j = 0; j < n; ++j) norm(j) = a.col(j).norm() > 0.0 ? a.col(j).norm() : 1.0;
  const Eigen::MatrixXd as = a * norm.cwiseInverse().asDiagonal();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  std::vector<bool> passive(static_cast<std::size_t>(n), false);
  auto solve_passive = [&](Eigen::VectorXd* z) {
    std::vector<Eigen::Index> idx;
    for (Eigen::Index j = 0; j < n; ++j) if (passive[j]) idx.push_back(j);
    z->setZero(n);
    if (idx.empty()) return;
    Eigen::MatrixXd sub(as.rows(), static_cast<Eigen::Index>(idx.size()));
    for (std::size_t c = 0; c < idx.size(); ++c) sub.col(static_cast<Eigen::Index>(c)) = as.col(idx[c]);
    const Eigen::VectorXd zs = sub.colPivHouseholderQr().solve(y);
    for (std::size_t c = 0; c < idx.size(); ++c) (*z)(idx[c]) = zs(static_cast<Eigen::Index>(c));
  };
  const double tolerance = 1e-12 * std::max(1.0, (as.transpose() * y).cwiseAbs().maxCoeff());
  for (int outer = 0; outer < 3 * n + 3; ++outer) {
    const Eigen::VectorXd w = as.transpose() * (y - as * x);
    Eigen::Index best = -1;
    for (Eigen::Index j = 0; j < n; ++j) {
      if (!passive[j] && w(j) > tolerance && (best < 0 || w(j) > w(best))) best = j;
    }
    if (best < 0) break;
    passive[best] = true;
    for (int inner = 0; inner < 3 * n + 3; ++inner) {
      Eigen::VectorXd z;
      solve_passive(&z);
      bool feasible = true;
      for (Eigen::Index j = 0; j < n; ++j) if (passive[j] && z(j) <= 0.0) feasible = false;
      if (feasible) {
        x = z;
        break;
      }
      double alpha = 1.0;
      for (Eigen::Index j = 0; j < n; ++j) {
        if (passive[j] && z(j) <= 0.0) alpha = std::min(alpha, x(j) / (x(j) - z(j)));
      }
      x += alpha * (z - x);
      for (Eigen::Index j = 0; j < n; ++j) {
        if (passive[j] && x(j) <= 1e-14) {
          passive[j] = false;
          x(j) = 0.0;
        }
      }
    }
  }
  return x.cwiseQuotient(norm);
}

namespace {

// NNLS over the columns of `mask`, with column `held` (if >= 0) fixed at `held_value`.
Eigen::VectorXd SolveMasked(const LinearProblem& p, unsigned mask, int held, double held_value) {
  std::vector<Eigen::Index> cols;
  for (Eigen::Index j = 0; j < p.a.cols(); ++j) {
    if ((mask >> j) & 1u && j != held) cols.push_back(j);
  }
  Eigen::VectorXd target = p.y;
  if (held >= 0) target -= held_value * p.a.col(held);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(p.a.cols());
  if (held >= 0) x(held) = held_value;
  if (cols.empty()) return x;
  Eigen::MatrixXd sub(p.a.rows(), static_cast<Eigen::Index>(cols.size()));
  for (std::size_t c = 0; c < cols.size(); ++c) sub.col(static_cast<Eigen::Index>(c)) = p.a.col(cols[c]);
  const Eigen::VectorXd xs = NonNegativeLeastSquares(sub, target);
  for (std::size_t c = 0; c < cols.size(); ++c) x(cols[c]) = xs(static_cast<Eigen::Index>(c));
  return x;
}

}  // namespace

Eigen::VectorXd SolveSubset(const LinearProblem& p, unsigned free_mask) {
  return SolveMasked(p, free_mask, -1, 0.0);
}

SubsetChoice SelectSubsetByAic(const LinearProblem& p) {
  const auto n = static_cast<unsigned>(p.a.cols());
  std::vector<Eigen::VectorXd> xs(1u << n);
  std::vector<double> costs(1u << n);
  bool any_likelihood = false;
  for (unsigned mask = 0; mask < (1u << n); ++mask) {
    xs[mask] = SolveSubset(p, mask);
    costs[mask] = LikelihoodCost(p, xs[mask]);
    any_likelihood = any_likelihood || std::isfinite(costs[mask]);
  }
  // No subset's covariance could be formed: the weight held (W0) scores them all.
  if (!any_likelihood) {
    for (unsigned mask = 0; mask < (1u << n); ++mask) costs[mask] = p.Chi2(xs[mask]);
  }
  SubsetChoice best;
  bool have = false;
  std::vector<double> scores(1u << n);
  for (unsigned mask = 0; mask < (1u << n); ++mask) {
    SubsetChoice c;
    c.mask = mask;
    c.x = xs[mask];
    c.chi2 = p.Chi2(c.x);
    c.score = costs[mask] + 2.0 * std::popcount(mask);
    scores[mask] = c.score;
    if (!std::isfinite(c.score)) continue;
    const bool better = !have || c.score < best.score - 1e-9 * std::max(1.0, best.score) ||
                        (std::abs(c.score - best.score) <= 1e-9 * std::max(1.0, best.score) &&
                         std::popcount(mask) < std::popcount(best.mask));
    if (better) {
      best = c;
      have = true;
    }
  }
  best.competitive = {best.mask};
  for (unsigned mask = 0; mask < (1u << n); ++mask) {
    const bool superset = (mask & best.mask) == best.mask;
    const bool one_more = superset && std::popcount(mask) == std::popcount(best.mask) + 1;
    if ((!superset && scores[mask] <= best.score + kCompetitiveAic) ||
        (one_more && scores[mask] <= best.score + kSupportedTermAic)) {
      best.competitive.push_back(mask);
    }
  }
  return best;
}

ProfileRange ProfileInterval(const LinearProblem& p, unsigned free_mask, int j, double delta) {
  return ProfileInterval(p, free_mask, j, [delta](double) { return delta; });
}

Eigen::MatrixXd FreeColumns(const LinearProblem& p, unsigned free_mask, int j, Eigen::Index* at_j) {
  std::vector<Eigen::Index> cols;
  *at_j = 0;
  for (Eigen::Index k = 0; k < p.a.cols(); ++k) {
    if (!((free_mask >> k) & 1u)) continue;
    if (k == j) *at_j = static_cast<Eigen::Index>(cols.size());
    cols.push_back(k);
  }
  Eigen::MatrixXd sub(p.a.rows(), static_cast<Eigen::Index>(cols.size()));
  for (std::size_t c = 0; c < cols.size(); ++c) sub.col(static_cast<Eigen::Index>(c)) = p.a.col(cols[c]);
  return sub;
}

double ProfileStandardError(const LinearProblem& p, unsigned free_mask, int j) {
  Eigen::Index at = 0;
  const Eigen::MatrixXd sub = FreeColumns(p, free_mask, j, &at);
  const Eigen::MatrixXd cov = (sub.transpose() * sub).completeOrthogonalDecomposition().pseudoInverse();
  return std::sqrt(std::max(cov(at, at), 0.0));
}

ProfileRange BoundedProfileInterval(const LinearProblem& p, unsigned free_mask, int j, double level,
                                    double offset) {
  const double sigma = ProfileStandardError(p, free_mask, j);
  return ProfileInterval(p, free_mask, j, [level, sigma, offset](double t) {
    return BoundedLikelihoodRatioThreshold(level, sigma > 0.0 ? std::max(t, 0.0) / sigma : 1e300) - offset;
  });
}

Eigen::VectorXd SolveHeld(const LinearProblem& p, unsigned free_mask, int j, double t) {
  return SolveMasked(p, free_mask, j, t);
}

namespace {

// q: p's design and target whitened by w, p.free_directions projected out.
void WhitenBy(const LinearProblem& p, const Eigen::MatrixXd& w, LinearProblem* q) {
  q->a = w * p.design;
  q->y = w * p.target;
  if (p.free_directions.cols() > 0) {
    const Eigen::MatrixXd f = w * p.free_directions;
    const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(f);
    q->a -= f * cod.solve(q->a);
    q->y -= f * cod.solve(q->y);
  }
}

// log |det w|.
double LogAbsDeterminant(const Eigen::MatrixXd& w) {
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(w);
  return lu.matrixLU().diagonal().cwiseAbs().array().log().sum();
}

}  // namespace

bool WhitenedAt(const LinearProblem& p, const Eigen::VectorXd& x, LinearProblem* q) {
  Eigen::MatrixXd w;
  if (!p.whitening_at || !p.whitening_at(x, &w)) return false;
  WhitenBy(p, w, q);
  return true;
}

bool GoodnessOfFitChi2(const LinearProblem& p, unsigned mask, double* chi2) {
  LinearProblem own;
  if (!WhitenedAt(p, SolveSubset(p, mask), &own)) return false;
  const Eigen::VectorXd x = SolveSubset(own, mask);
  Eigen::MatrixXd w;
  if (!p.whitening_at(x, &w)) return false;
  const Eigen::Index n = w.rows();
  const Eigen::VectorXd offset = p.offset.size() == n ? p.offset : Eigen::VectorXd::Zero(n);
  const Eigen::VectorXd mean = p.design * x + offset;
  const Eigen::VectorXd curve = p.target + offset;
  // Omega = W^-1 W^-T: its diagonal from the rows of W^-1.
  const Eigen::MatrixXd root = w.partialPivLu().solve(Eigen::MatrixXd::Identity(n, n));
  Eigen::VectorXd r(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const double sd = root.row(k).norm();
    const double mu = std::max(mean(k), 1e-300 * sd);
    const double nu = 2.0 * mu * mu / (sd * sd);
    const double v = 2.0 / (9.0 * nu);
    const double ratio = std::max(curve(k), 0.0) / mu;
    const double z = (std::cbrt(ratio) - (1.0 - v)) / std::sqrt(v);
    r(k) = sd * std::clamp(z, -1e6, 1e6);
  }
  Eigen::VectorXd v = w * r;
  if (p.free_directions.cols() > 0) {
    const Eigen::MatrixXd f = w * p.free_directions;
    v -= f * Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(f).solve(v);
  }
  *chi2 = v.squaredNorm();
  return true;
}

double LikelihoodCost(const LinearProblem& p, const Eigen::VectorXd& x) {
  if (!p.whitening_at) return p.Chi2(x);
  // A model of no terms has no covariance, and one whose covariance cannot be formed no likelihood.
  Eigen::MatrixXd w;
  if (!(x.array() > 0.0).any() || !p.whitening_at(x, &w)) return std::numeric_limits<double>::infinity();
  LinearProblem q;
  WhitenBy(p, w, &q);
  // log det Omega(x) = -2 log |det W(x)|, taken relative to W0's so that the cost stays on chi2's
  // scale.
  const double w0 = p.whitening.size() > 0 ? LogAbsDeterminant(p.whitening) : 0.0;
  return q.Chi2(x) - 2.0 * (LogAbsDeterminant(w) - w0);
}

double ProfileStatistic(const LinearProblem& p, unsigned free_mask, int j, double t) {
  LinearProblem q;
  if (WhitenedAt(p, SolveMasked(p, free_mask, j, t), &q)) {
    return q.Chi2(SolveMasked(q, free_mask, j, t)) - q.Chi2(SolveSubset(q, free_mask));
  }
  return p.Chi2(SolveMasked(p, free_mask, j, t)) - p.Chi2(SolveSubset(p, free_mask));
}

double ProfileEnd(const LinearProblem& p, unsigned free_mask, int j,
                  const std::function<double(double t)>& delta, bool upper, double relative_tolerance) {
  const double t_hat = SolveSubset(p, free_mask)(j);
  // Delta(t) <= delta inside the range (header).
  auto inside = [&](double t) { return ProfileStatistic(p, free_mask, j, t) <= delta(t); };
  const double tolerance = relative_tolerance > 0.0 ? relative_tolerance : p.whitening_at ? 1e-6 : 1e-9;
  // The estimate is inside by construction: each end is bracketed from it outwards (with W0 held
  // the statistic is convex in t, so the end is its one root; with whitening_at it need not be,
  // and a held value beyond a rejected one is not reached: header).
  const double at_estimate = delta(t_hat);
  if (!(at_estimate >= 0.0)) return std::numeric_limits<double>::quiet_NaN();
  const double column = p.a.col(j).norm();
  double step = column > 0.0 ? std::sqrt(at_estimate) / column : 1.0;  // the end with the others fixed
  step = std::max(step, 1e-6 * t_hat);
  if (!upper) {
    if (t_hat <= 0.0) return 0.0;
    double lo = 0.0, hi = t_hat;  // lo rejected, hi accepted
    for (;;) {
      const double t = std::max(t_hat - step, 0.0);
      if (!inside(t)) {
        lo = t;
        break;
      }
      if (t <= 0.0) return 0.0;
      hi = t;
      step *= 2.0;
    }
    for (int i = 0; i < 60 && hi - lo > tolerance * hi; ++i) {
      const double mid = 0.5 * (lo + hi);
      (inside(mid) ? hi : lo) = mid;
    }
    return 0.5 * (lo + hi);
  }
  double lo = t_hat, hi = t_hat + step;
  bool bracketed = false;
  for (int i = 0; i < 80; ++i) {
    if (!inside(hi)) {
      bracketed = true;
      break;
    }
    lo = hi;
    step *= 2.0;
    hi = t_hat + step;
  }
  if (!bracketed) return std::numeric_limits<double>::infinity();  // not bounded up to 2^80 first steps
  for (int i = 0; i < 60 && hi - lo > tolerance * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (inside(mid) ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

ProfileRange ProfileInterval(const LinearProblem& p, unsigned free_mask, int j,
                             const std::function<double(double t)>& delta) {
  ProfileRange r;
  r.upper = ProfileEnd(p, free_mask, j, delta, true);
  r.lower = ProfileEnd(p, free_mask, j, delta, false);
  return r;
}

void SetProfileRanges(const LinearProblem& p, const std::vector<unsigned>& free_masks, int j,
                      double scale, CoefficientEstimate* e, const std::vector<LinearProblem>& alternatives) {
  auto root = [scale](double x) { return std::sqrt(std::max(x * scale, 0.0)); };
  ProfileRange r68{std::numeric_limits<double>::infinity(), 0.0}, r95 = r68;
  double upper = 0.0;
  auto hull = [](ProfileRange* h, const ProfileRange& r) {
    if (std::isnan(r.lower) || std::isnan(r.upper)) return;  // an alternative that adds nothing
    h->lower = std::min(h->lower, r.lower);
    h->upper = std::max(h->upper, r.upper);
  };
  // A term not determined is profiled with it free (its lower ends are then 0); subsets that differ
  // only in term j give the same profile, so each is profiled once.
  std::vector<unsigned> masks;
  for (unsigned m : free_masks) {
    if (std::find(masks.begin(), masks.end(), m | (1u << j)) == masks.end()) masks.push_back(m | (1u << j));
  }
  for (unsigned mask : masks) {
    const ProfileRanges ranges = CalibratedProfileIntervals(p, mask, j);
    hull(&r68, ranges.at68);
    hull(&r95, ranges.at95);
    if (!e->fitted) upper = std::max(upper, ProfileInterval(p, mask, j, kProfileDeltaUpper95).upper);
    // The alternatives within the widest critical value of p's minimum (header) whose estimate of
    // x_j differs from p's by more than kTradeShift of its standard error.
    if (alternatives.empty()) continue;
    const Eigen::VectorXd fit_x = SolveSubset(p, mask);
    const double fit_chi2 = p.Chi2(fit_x);
    const double sigma = ProfileStandardError(p, mask, j);
    for (const LinearProblem& alternative : alternatives) {
      const Eigen::VectorXd x = SolveSubset(alternative, mask);
      const double offset = std::max(alternative.Chi2(x) - fit_chi2, 0.0);
      if (!(offset < kProfileDelta95) || !(std::abs(x(j) - fit_x(j)) > kTradeShift * sigma)) continue;
      const ProfileRanges more = CalibratedProfileIntervals(alternative, mask, j, offset);
      hull(&r68, more.at68);
      hull(&r95, more.at95);
      if (!e->fitted && offset < kProfileDeltaUpper95) {
        const double end = ProfileInterval(alternative, mask, j, kProfileDeltaUpper95 - offset).upper;
        if (!std::isnan(end)) upper = std::max(upper, end);
      }
    }
  }
  // Every range was rejected at its own estimate (cannot happen for p, whose offset is 0).
  if (r68.lower > r68.upper) r68 = {0.0, 0.0};
  if (r95.lower > r95.upper) r95 = {0.0, 0.0};
  e->has_intervals = true;
  e->interval68_si = {root(r68.lower), root(r68.upper)};
  e->interval95_si = {root(r95.lower), root(r95.upper)};
  if (e->fitted) {
    // Where the problem is an expansion at the fit (log-WLS; the linear terms of a parametric
    // fit), its minimum can sit off the fit's own value when the fit is poor (ADIS16405 Gyro_Z,
    // chi2 4.6e5 on 50 dof: Q 21.53 urad, 95 % [21.74, 23.9]): the ranges then reach the value.
    for (auto* r : {&e->interval68_si, &e->interval95_si}) {
      (*r)[0] = std::min((*r)[0], e->value_si);
      (*r)[1] = std::max((*r)[1], e->value_si);
    }
  }
  if (!e->fitted) {
    e->has_upper_limit = true;
    e->upper_limit_si = root(upper);
  }
}

void JudgeGoodnessOfFit(const LinearProblem& p, const std::vector<unsigned>& free_masks, FitSummary* summary) {
  if (!p.whitening_at) return;
  const unsigned chosen = free_masks.empty() ? (1u << p.a.cols()) - 1u : free_masks.front();
  double chi2 = 0.0;
  if (GoodnessOfFitChi2(p, chosen, &chi2)) SetGoodnessOfFit(chi2, summary);
}

void SetFitProfileRanges(LinearProblem p, const std::vector<unsigned>& free_masks, const std::vector<int>& terms,
                         const std::vector<double>& scale, FitSummary* summary,
                         std::vector<LinearProblem> alternatives) {
  // On a poor fit the misfit this rule is about stays under every covariance (header).
  if (IsPoorFit(*summary)) {
    p.whitening_at = nullptr;
    for (LinearProblem& a : alternatives) a.whitening_at = nullptr;
  }
  for (std::size_t j = 0; j < terms.size(); ++j) {
    SetProfileRanges(p, free_masks, static_cast<int>(j), scale[j], &summary->coefficients[terms[j]], alternatives);
  }
}

}  // namespace allanlab::estimators
