// Coverage of a coefficient's profile interval after the AIC subset choice, on a linear Gaussian
// problem shaped like the short-tau end of an Allan curve (a white-noise term N and a
// quantization-like term Q with Q = 0, whitened so each row has unit noise). Expected values are
// the nominal levels, not this code: the intervals of the chosen subset alone under-cover (when AIC
// takes a spurious Q, N traded against it sits low), the hull over the competitive subsets
// (linear_profile.h) covers within 3 points of nominal, the fit's target (at 8000 draws: chosen
// subset 64.4 % and 93.3 %, hull 68.3 % and 94.0 %; the binomial sd at 4000 draws is 0.74 and 0.34
// points, so the band is 4 and 9 sd wide and a method 1 point further off fails). With the
// one-term superset the data support at one sigma also in the hull, 4000 draws: hull 2808 (70.2 %)
// and 3768 (94.2 %).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "estimators/fit/linear_profile.h"

namespace allanlab::estimators {
namespace {

constexpr int kDraws = 4000;

TEST(SelectionCoverage, HullOverCompetitiveSubsetsCoversWhereTheChosenSubsetDoesNot) {
  constexpr int kRows = 30;
  Eigen::MatrixXd a(kRows, 2);
  for (int i = 0; i < kRows; ++i) {
    const double tau = std::pow(2.0, i / 3.0);
    a(i, 1) = std::sqrt(2000.0 / tau);  // N: expected avar / its sd falls as tau^-1/2
    a(i, 0) = a(i, 1) / tau;            // Q: one power of tau steeper
  }
  const Eigen::Vector2d truth(0.0, 1.0);
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g;
  int chosen_only[2] = {0, 0}, hull[2] = {0, 0}, spurious = 0;
  const double levels[2] = {kProfileLevel68, kProfileLevel95};
  for (int d = 0; d < kDraws; ++d) {
    LinearProblem p;
    p.a = a;
    p.y = a * truth;
    for (int i = 0; i < kRows; ++i) p.y(i) += g(rng);
    const SubsetChoice choice = SelectSubsetByAic(p);
    spurious += (choice.mask & 1u) != 0;
    CoefficientEstimate alone, all;
    alone.fitted = all.fitted = choice.x(1) > 0.0;
    alone.value_si = all.value_si = std::sqrt(std::max(choice.x(1), 0.0));
    SetProfileRanges(p, {choice.mask}, 1, 1.0, &alone);
    SetProfileRanges(p, choice.competitive, 1, 1.0, &all);
    // scale 1: the ranges are of sqrt(x_N); the truth's root is 1.
    for (int l = 0; l < 2; ++l) {
      const auto& ra = l == 0 ? alone.interval68_si : alone.interval95_si;
      const auto& rh = l == 0 ? all.interval68_si : all.interval95_si;
      chosen_only[l] += ra[0] <= 1.0 && 1.0 <= ra[1];
      hull[l] += rh[0] <= 1.0 && 1.0 <= rh[1];
    }
  }
  std::printf("spurious Q in %d of %d draws\n", spurious, kDraws);
  for (int l = 0; l < 2; ++l) {
    std::printf("level %.3f: chosen subset %d, hull %d of %d\n", levels[l], chosen_only[l], hull[l],
                kDraws);
    EXPECT_NEAR(hull[l] / double(kDraws), levels[l], 0.03) << levels[l];
  }
  // What the hull fixes: the chosen subset alone is short of nominal at 68.3 % (5 sd below).
  EXPECT_LT(chosen_only[0] / double(kDraws), levels[0] - 0.025);
}

}  // namespace
}  // namespace allanlab::estimators
