// The bounded profile intervals against Feldman & Cousins (Phys. Rev. D 57, 3873, 1998), Gaussian
// mean with mu >= 0 and unit sigma: their published belt, and coverage by Monte Carlo against the
// nominal level (not against this code), where the fixed chi2_1 quantile over-covers.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "estimators/fit/bounded_threshold.h"
#include "estimators/fit/linear_profile.h"

namespace allanlab::estimators {
namespace {

// One unit column: the estimate of x is the observation z, sigma 1.
LinearProblem Observed(double z) {
  LinearProblem p;
  p.a = Eigen::MatrixXd::Constant(1, 1, 1.0);
  p.y = Eigen::VectorXd::Constant(1, z);
  return p;
}

TEST(BoundedThreshold, ChiSquareFarFromTheBoundaryAndNormalQuantileAtIt) {
  EXPECT_NEAR(BoundedLikelihoodRatioThreshold(0.6826894921370859, 10.0), 1.0, 1e-9);
  EXPECT_NEAR(BoundedLikelihoodRatioThreshold(0.95, 10.0), 3.841458820694124, 1e-9);
  EXPECT_NEAR(BoundedLikelihoodRatioThreshold(0.95, 0.0), 1.6448536269514722 * 1.6448536269514722, 1e-9);
  // Between, it rises with the distance from the boundary.
  double previous = 0.0;
  for (double s : {0.0, 0.25, 0.5, 1.0, 1.5, 1.9}) {
    const double c = BoundedLikelihoodRatioThreshold(0.95, s);
    EXPECT_GT(c, previous) << s;
    previous = c;
  }
}

TEST(BoundedThreshold, FeldmanCousinsPublishedBelt) {
  // Their table X (90 % C.L.): an observation at 0 gives [0, 1.64]; the 68.27 % belt gives
  // [0, 1.00]; and the 90 % belt turns from an upper limit to a two-sided interval at x = 1.28.
  const ProfileRange at_zero90 = BoundedProfileInterval(Observed(0.0), 1u, 0, 0.90);
  EXPECT_EQ(at_zero90.lower, 0.0);
  EXPECT_NEAR(at_zero90.upper, 1.64, 0.005);
  EXPECT_NEAR(BoundedProfileInterval(Observed(0.0), 1u, 0, 0.6827).upper, 1.00, 0.005);
  EXPECT_EQ(BoundedProfileInterval(Observed(1.27), 1u, 0, 0.90).lower, 0.0);
  EXPECT_GT(BoundedProfileInterval(Observed(1.30), 1u, 0, 0.90).lower, 0.0);
}

TEST(BoundedThreshold, CoversAtTheNominalLevelWhereTheFixedQuantileOverCovers) {
  constexpr int kDraws = 400;
  std::mt19937_64 rng(20261124);
  std::normal_distribution<double> g;
  for (double mu : {0.0, 0.5, 3.0}) {
    for (double level : {0.6826894921370859, 0.95}) {
      int bounded = 0, fixed = 0;
      for (int i = 0; i < kDraws; ++i) {
        const LinearProblem p = Observed(mu + g(rng));
        const ProfileRange r = BoundedProfileInterval(p, 1u, 0, level);
        bounded += r.lower <= mu && mu <= r.upper;
        const double delta = level > 0.9 ? kProfileDelta95 : kProfileDelta68;
        const ProfileRange f = ProfileInterval(p, 1u, 0, delta);
        fixed += f.lower <= mu && mu <= f.upper;
      }
      const double sd = std::sqrt(level * (1.0 - level) / kDraws);
      EXPECT_NEAR(bounded / double(kDraws), level, 3.0 * sd) << "mu " << mu << " level " << level;
      // At the boundary the fixed quantile covers 0.5 + 0.5 level (84 % at 68.3 %).
      if (mu == 0.0) {
        EXPECT_NEAR(fixed / double(kDraws), 0.5 + 0.5 * level, 3.0 * sd) << level;
      }
    }
  }
}

}  // namespace
}  // namespace allanlab::estimators
