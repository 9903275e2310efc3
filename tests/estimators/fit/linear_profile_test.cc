// The linear problem's subset choice and profile ranges against closed forms: away from the
// boundary the profile interval of a linear least-squares problem is x_hat_j +- sqrt(delta) sigma_j
// with sigma_j^2 the j-th diagonal element of (A'A)^-1; at the boundary the upper limit solves
// (t - x_hat_j)^2 / sigma_j^2 = delta from the constrained minimum.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "estimators/fit/linear_profile.h"

namespace allanlab::estimators {
namespace {

LinearProblem Random(int rows, int cols, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g;
  LinearProblem p;
  p.a.resize(rows, cols);
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) p.a(i, j) = g(rng) + (j == 0 ? 3.0 : 0.0);
  }
  p.y.resize(rows);
  for (int i = 0; i < rows; ++i) p.y(i) = g(rng);
  return p;
}

TEST(LinearProfile, InteriorIntervalIsEstimatePlusMinusRootDeltaSigma) {
  LinearProblem p = Random(40, 3, 1);
  const Eigen::VectorXd truth = Eigen::Vector3d(5.0, 2.0, 4.0);
  p.y = p.a * truth + 0.1 * p.y;  // well inside x > 0
  const Eigen::MatrixXd cov = (p.a.transpose() * p.a).inverse();
  const Eigen::VectorXd x = (p.a.transpose() * p.a).ldlt().solve(p.a.transpose() * p.y);
  for (int j = 0; j < 3; ++j) {
    for (double delta : {kProfileDelta68, kProfileDelta95}) {
      const ProfileRange r = ProfileInterval(p, 7u, j, delta);
      const double half = std::sqrt(delta * cov(j, j));
      EXPECT_NEAR(r.lower, x(j) - half, 1e-7 * half) << j;
      EXPECT_NEAR(r.upper, x(j) + half, 1e-7 * half) << j;
    }
  }
}

TEST(LinearProfile, UpperLimitAtTheBoundary) {
  // One column: chi2(t) = |y - a t|^2 = chi2_min + (t - t_hat)^2 / sigma^2, t_hat < 0 so the
  // constrained minimum is at 0 and the limit solves (t - t_hat)^2 - t_hat^2 = delta sigma^2.
  LinearProblem p;
  p.a = Eigen::MatrixXd::Constant(10, 1, 1.0);
  p.y = Eigen::VectorXd::Constant(10, -0.2);
  const double sigma2 = 1.0 / 10.0, t_hat = -0.2;
  const ProfileRange r = ProfileInterval(p, 1u, 0, kProfileDeltaUpper95);
  EXPECT_EQ(r.lower, 0.0);
  EXPECT_NEAR(r.upper, t_hat + std::sqrt(t_hat * t_hat + kProfileDeltaUpper95 * sigma2), 1e-9);
}

TEST(LinearProfile, AicKeepsTheTermsThatLowerChi2ByMoreThanTwo) {
  // Columns 0 and 1 in the data, column 2 absent: the chosen subset is {0, 1}.
  LinearProblem p = Random(60, 3, 2);
  p.y = p.a.col(0) * 4.0 + p.a.col(1) * 3.0 + 0.05 * p.y;
  const SubsetChoice c = SelectSubsetByAic(p);
  EXPECT_EQ(c.mask, 3u);
  // The score is chi2 + 2 k of the chosen subset and no other subset scores lower.
  EXPECT_NEAR(c.score, p.Chi2(c.x) + 4.0, 1e-9);
  for (unsigned m = 0; m < 8; ++m) {
    const Eigen::VectorXd x = SolveSubset(p, m);
    EXPECT_GE(p.Chi2(x) + 2.0 * __builtin_popcount(m), c.score - 1e-9) << m;
  }
}

TEST(LinearProfile, RangesReachTheFitsValueWhenTheExpansionsMinimumSitsOffIt) {
  // An expansion at a poor fit: its minimum (x = 4, sigma 0.1) is not the fit's value (x = 3).
  LinearProblem p;
  p.a = Eigen::MatrixXd::Constant(100, 1, 1.0);
  p.y = Eigen::VectorXd::Constant(100, 4.0);
  CoefficientEstimate e;
  e.fitted = true;
  e.value_si = std::sqrt(3.0);
  SetProfileRanges(p, {1u}, 0, 1.0, &e);
  EXPECT_LE(e.interval68_si[0], e.value_si);
  EXPECT_LE(e.interval95_si[0], e.value_si);
  EXPECT_NEAR(e.interval95_si[1], std::sqrt(4.0 + 0.1 * std::sqrt(kProfileDelta95)), 1e-6);
}

// Alternative problems (the same column at another value of a parameter the fit held): a term's
// range is the union of each problem's range at the critical value less its offset above the fit.
// One column, sigma 1: the fit x = 2 (Delta(t) = (2 - t)^2); an alternative with x = 5 whose
// minimum lies 2.25 above extends the 95 % range to 5 + sqrt(3.841 - 2.25) = 6.26, and adds
// nothing at 68.3 % (2.25 > 1); one 4 above (beyond 3.841) adds nothing at all.
TEST(LinearProfile, AlternativesExtendTheRangesByTheirOffsets) {
  auto problem = [](double x_hat, double offset) {
    LinearProblem p;
    p.a = Eigen::MatrixXd(2, 1);
    p.a << 1.0, 0.0;
    p.y = Eigen::VectorXd(2);
    p.y << x_hat, std::sqrt(offset);
    return p;
  };
  const LinearProblem fit = problem(2.0, 0.0);
  CoefficientEstimate alone, near, far;
  for (CoefficientEstimate* e : {&alone, &near, &far}) {
    e->fitted = true;
    e->value_si = std::sqrt(2.0);
  }
  SetProfileRanges(fit, {1u}, 0, 1.0, &alone);
  SetProfileRanges(fit, {1u}, 0, 1.0, &near, {problem(5.0, 2.25)});
  SetProfileRanges(fit, {1u}, 0, 1.0, &far, {problem(5.0, 4.0)});
  EXPECT_NEAR(alone.interval95_si[1], std::sqrt(2.0 + std::sqrt(kProfileDelta95)), 1e-6);
  EXPECT_NEAR(near.interval95_si[1], std::sqrt(5.0 + std::sqrt(kProfileDelta95 - 2.25)), 1e-6);
  EXPECT_EQ(near.interval95_si[0], alone.interval95_si[0]);
  EXPECT_EQ(near.interval68_si[0], alone.interval68_si[0]);
  EXPECT_EQ(near.interval68_si[1], alone.interval68_si[1]);
  EXPECT_EQ(far.interval95_si[1], alone.interval95_si[1]);
}

}  // namespace
}  // namespace allanlab::estimators
