// experiments/family_expectation.h against the closed forms of docs/theory.md §2.1-2.3 and §2.10
// (white, quantization and random-walk rate noise), against plain_noise.h's own AVAR of its
// flicker (another summation of the same autocovariance), and the total variance against NIST
// SP 1065's bias factor 1 - a tau / T.
#include "experiments/family_expectation.h"

#include <cmath>

#include <gtest/gtest.h>

#include "experiments/plain_noise.h"

namespace allanlab::experiments {
namespace {

using estimators::Statistic;

Autocovariance Of(PlainNoise noise) {
  return [noise](std::int64_t k) { return PlainAutocovariance(noise, k); };
}

TEST(FamilyExpectation, WhiteRateNoiseClosedForms) {
  const auto r = Of(PlainNoise::kWhite);
  for (std::int64_t m : {1, 2, 3, 8, 64}) {
    const double md = static_cast<double>(m);
    EXPECT_NEAR(FamilyExpectation(Statistic::kAllanOverlapping, m, 4096, 1.0, r), 1.0 / md, 1e-12);
    EXPECT_NEAR(FamilyExpectation(Statistic::kHadamardOverlapping, m, 4096, 1.0, r), 1.0 / md, 1e-12);
    EXPECT_NEAR(FamilyExpectation(Statistic::kModifiedAllan, m, 4096, 1.0, r),
                (md * md + 1.0) / (2.0 * md * md * md), 1e-12);
    // TVAR = tau^2 MVAR / 3 with tau = m tau0 (tau0 = 0.5 s here).
    EXPECT_NEAR(FamilyExpectation(Statistic::kTime, m, 4096, 0.5, r),
                0.25 * md * md * (md * md + 1.0) / (2.0 * md * md * md) / 3.0, 1e-12);
  }
}

TEST(FamilyExpectation, QuantizationClosedForms) {
  // Differenced white angle of unit variance: Q = 1, tau0 = 1 (docs/theory.md §2.1).
  const auto r = Of(PlainNoise::kQuantization);
  for (std::int64_t m : {1, 2, 5, 16, 128}) {
    const double avar = 3.0 / static_cast<double>(m * m);
    EXPECT_NEAR(FamilyExpectation(Statistic::kAllanNonOverlapping, m, 4096, 1.0, r), avar, 1e-12);
    EXPECT_NEAR(FamilyExpectation(Statistic::kHadamardNonOverlapping, m, 4096, 1.0, r), 10.0 / 9.0 * avar, 1e-12);
    EXPECT_NEAR(FamilyExpectation(Statistic::kModifiedAllan, m, 4096, 1.0, r), avar / static_cast<double>(m), 1e-12);
  }
}

TEST(FamilyExpectation, RandomWalkClosedFormAndLargeMRatios) {
  const auto r = Of(PlainNoise::kRandomWalk);
  for (std::int64_t m : {1, 2, 3, 10, 100}) {
    const double md = static_cast<double>(m);
    EXPECT_NEAR(FamilyExpectation(Statistic::kAllanOverlapping, m, 4096, 1.0, r),
                (2.0 * md * md + 1.0) / (6.0 * md), 1e-9 * md);
  }
  const double avar = FamilyExpectation(Statistic::kAllanOverlapping, 400, 4096, 1.0, r);
  EXPECT_NEAR(FamilyExpectation(Statistic::kHadamardOverlapping, 400, 4096, 1.0, r) / avar, 0.5, 0.002);
  EXPECT_NEAR(FamilyExpectation(Statistic::kModifiedAllan, 400, 4096, 1.0, r) / avar, 0.825, 0.002);
}

TEST(FamilyExpectation, FlickerAvarMatchesPlainNoisesOwnSum) {
  const auto r = Of(PlainNoise::kFlicker);
  for (std::int64_t m : {1, 4, 32, 256}) {
    EXPECT_NEAR(FamilyExpectation(Statistic::kAllanOverlapping, m, 4096, 1.0, r),
                PlainExpectedAvar(PlainNoise::kFlicker, m), 1e-9);
  }
  // Large-m MVAR/AVAR of flicker FM: 0.674 (docs/theory.md §2.10).
  const double ratio = FamilyExpectation(Statistic::kModifiedAllan, 256, 4096, 1.0, r) /
                       FamilyExpectation(Statistic::kAllanOverlapping, 256, 4096, 1.0, r);
  EXPECT_NEAR(ratio, 0.674, 0.01);
}

TEST(FamilyExpectation, TotalVarianceFollowsNistBiasFactor) {
  // E[TOTVAR] ~ AVAR (1 - a tau / T), a = 0, 0.481, 0.750 for white, flicker, random walk FM
  // (NIST SP 1065, an approximation: within 1 % of AVAR at tau / T = 1/64).
  const std::int64_t n = 4096, m = 64;
  const double share = static_cast<double>(m) / static_cast<double>(n);
  const struct {
    PlainNoise noise;
    double a;
  } cases[] = {{PlainNoise::kWhite, 0.0}, {PlainNoise::kFlicker, 0.481}, {PlainNoise::kRandomWalk, 0.750}};
  for (const auto& c : cases) {
    const double avar = FamilyExpectation(Statistic::kAllanOverlapping, m, n, 1.0, Of(c.noise));
    const double total = FamilyExpectation(Statistic::kTotal, m, n, 1.0, Of(c.noise));
    EXPECT_NEAR(total / avar, 1.0 - c.a * share, 0.01) << PlainNoiseLabel(c.noise);
  }
  // Without edge centres (m = 1 has none) the total variance is the overlapping AVAR.
  EXPECT_NEAR(FamilyExpectation(Statistic::kTotal, 1, 100, 1.0, Of(PlainNoise::kWhite)), 1.0, 1e-12);
}

TEST(FamilyExpectation, RejectsTausOutOfReach) {
  const auto r = Of(PlainNoise::kWhite);
  EXPECT_THROW(FamilyExpectation(Statistic::kAllanOverlapping, 0, 100, 1.0, r), std::invalid_argument);
  EXPECT_THROW(FamilyExpectation(Statistic::kHadamardOverlapping, 40, 100, 1.0, r), std::invalid_argument);
  EXPECT_THROW(PlainAutocovariance(PlainNoise::kRandomWalkAveraged, 1), std::invalid_argument);
}

}  // namespace
}  // namespace allanlab::experiments
