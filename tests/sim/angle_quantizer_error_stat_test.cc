// The angle quantizer when the angle moves less than one LSB per sample (benchmark recordings
// #14, #40, #56: 0.3 LSB): its error is correlated from sample to sample and the white
// q^2 / (4 tau^2) overstates the shortest taus' AVAR (by 6.6 % at m = 1 on #14, |z| = 37 there
// on 1e6 samples). The exact error autocovariance (output_quantizer.h) must reproduce the Monte
// Carlo mean of the overlapping AVAR where the white approximation does not.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/monte_carlo.h"

namespace allanlab::sim {
namespace {

TEST(AngleQuantizerError, ClosedFormsAtTheLimits) {
  const AngleQuantizer q{0.1};
  // No motion: the error repeats itself (q^2/12); a bias of half an LSB per sample with no
  // noise alternates it: R_e(1) = q^2 (1/4 - 1/2 + 1/6) / 2 = -q^2/24.
  const std::vector<double> still = {0.0, 0.0};
  EXPECT_DOUBLE_EQ(q.ErrorAutocovariance(still, 0.0)[1], 0.01 / 12.0);
  EXPECT_NEAR(q.ErrorAutocovariance(still, 0.05)[1], -0.01 / 24.0, 1e-15);
  // D(1) = q^2: R_e(1) = (6 / pi^2) exp(-2 pi^2) R_e(0) ~ 1.6e-9 R_e(0), the busy-noise limit.
  const std::vector<double> busy = {0.0, 0.01};
  const auto e = q.ErrorAutocovariance(busy, 0.0);
  EXPECT_DOUBLE_EQ(e[0], 0.01 / 12.0);
  EXPECT_NEAR(e[1], 6.0 / (M_PI * M_PI) * std::exp(-2.0 * M_PI * M_PI) * e[0], 1e-3 * std::abs(e[1]));
  EXPECT_NEAR(AngleQuantizer::AvarFromError(1, 0.5, e), q.ApproximateAvar(0.5) - 4.0 * e[1] / 0.25, 1e-12 * e[0]);
}

TEST(AngleQuantizerError, ExactTheoryMatchesMonteCarloWhereTheWhiteApproximationFails) {
  // White rate noise whose angle moves 0.3 LSB (sd) per sample, plus a bias of 0.1 LSB per
  // sample: the error is correlated at lags 1-2 and modulated by the bias.
  constexpr double kFs = 100.0, kLsb = 1e-4;
  const double arw = 0.3 * kLsb * std::sqrt(kFs);  // sd of the angle increment = arw sqrt(tau0)
  SensorModel model = testing_support::SingleTermModel(WhiteRateNoise{arw}, kFs);
  model.bias_rad_per_s = 0.1 * kLsb * kFs;
  model.angle_quantizer = AngleQuantizer{kLsb};
  ASSERT_TRUE(model.ExpectedAvarIsExact());
  SensorModel unquantized = model;
  unquantized.angle_quantizer.reset();
  const auto check = testing_support::CheckQuantizerTheory(model, unquantized, 23, [&](std::int64_t m) {
    return model.angle_quantizer->ApproximateAvar(static_cast<double>(m) / kFs);
  });
  EXPECT_TRUE(check.exact);
  EXPECT_GT(check.white_worst_z, 8.0) << "the white approximation is indistinguishable here";
}

}  // namespace
}  // namespace allanlab::sim
