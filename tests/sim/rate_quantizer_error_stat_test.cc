// The rate quantizer on a band-limited signal whose noise per sample is below one LSB: its error
// is neither lsb^2/12 nor white, and the exact error autocovariance (output_quantizer.h) must
// reproduce the Monte Carlo mean of the overlapping AVAR where the white approximation does not.
// With subtractive dither the same coarse quantizer's error is white lsb^2/12 exactly (Schuchman's
// condition for uniform dither), which the Monte Carlo must show where rounding's theory fails.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/monte_carlo.h"

namespace allanlab::sim {
namespace {

// White rate noise through a point-sampled first-order 3 Hz low-pass at 100 Hz (lag-1
// correlation 0.83), then a rate LSB of 3 per-sample standard deviations, offset drawn per record:
// the signal mostly stays on one level for several samples.
SensorModel CoarselyQuantizedBandLimited() {
  SensorModel model = testing_support::SingleTermModel(WhiteRateNoise{0.002}, 100.0);
  model.band_limit = BandLimit{LowPassKind::kFirstOrder, 3.0, 8, OutputSampling::kPoint};
  RateQuantizer q;
  q.random_offset = true;
  // Per-sample SD of the band-limited white noise: sqrt(R(0)).
  const double sd = std::sqrt(model.GaussianAutocovariance(1)[0]);
  q.lsb_rad_per_s = 3.0 * sd;
  model.rate_quantizer = q;
  return model;
}

TEST(RateQuantizerError, ZeroLagIsUniformAndBusyNoiseIsWhite) {
  RateQuantizer q{0.1, true};
  // D(1) = 2 (R(0) - R(1)) = 2 lsb^2 -> exp(-4 pi^2) ~ 7e-18: decorrelated at lag 1.
  const std::vector<double> busy = {0.02, 0.01, 0.01};
  const auto e = q.ErrorAutocovariance(busy);
  EXPECT_DOUBLE_EQ(e[0], 0.01 / 12.0);
  EXPECT_LT(e[1], 1e-18);
  // A signal that does not move repeats its error.
  const std::vector<double> still = {1.0, 1.0};
  EXPECT_DOUBLE_EQ(q.ErrorAutocovariance(still)[1], 0.01 / 12.0);
}

TEST(RateQuantizerError, ExactTheoryMatchesMonteCarloWhereTheWhiteApproximationFails) {
  const SensorModel model = CoarselyQuantizedBandLimited();
  ASSERT_TRUE(model.ExpectedAvarIsExact());
  SensorModel unquantized = model;
  unquantized.rate_quantizer.reset();
  const auto check = testing_support::CheckQuantizerTheory(
      model, unquantized, 17, [&](std::int64_t m) { return model.rate_quantizer->ApproximateAvar(m); });
  EXPECT_TRUE(check.exact);
  EXPECT_GT(check.white_worst_z, 8.0) << "the white approximation is indistinguishable here";
}

TEST(RateQuantizerError, SubtractiveDitherLeavesWhiteUniformErrorOnACoarseGrid) {
  SensorModel dithered = CoarselyQuantizedBandLimited();
  dithered.rate_quantizer->subtractive_dither = true;
  ASSERT_TRUE(dithered.ExpectedAvarIsExact());
  const auto e = dithered.rate_quantizer->ErrorAutocovariance(std::vector<double>{1.0, 1.0, 0.5});
  const double lsb2 = std::pow(dithered.rate_quantizer->lsb_rad_per_s, 2);
  EXPECT_DOUBLE_EQ(e[0], lsb2 / 12.0);
  EXPECT_EQ(e[1], 0.0);
  EXPECT_EQ(e[2], 0.0);
  SensorModel unquantized = dithered;
  unquantized.rate_quantizer.reset();
  const SensorModel rounded = CoarselyQuantizedBandLimited();
  // The alternative the Monte Carlo must reject: rounding's exact error (random offset).
  const auto check = testing_support::CheckQuantizerTheory(dithered, unquantized, 23, [&](std::int64_t m) {
    const RecordShape shape{1 << 14, AvarEstimatorKind::kOverlapping};
    return rounded.ExpectedAvar(m, shape) - unquantized.ExpectedAvar(m, shape);
  });
  EXPECT_TRUE(check.exact);
  EXPECT_GT(check.white_worst_z, 8.0) << "dither and rounding are indistinguishable here";
}

TEST(RateQuantizerError, SubtractiveDitherPutsTheSamplesOnNoGrid) {
  SensorModel model = CoarselyQuantizedBandLimited();
  model.rate_quantizer->subtractive_dither = true;
  const std::vector<double> y = model.Generate(5, 0, 4096);
  const double lsb = model.rate_quantizer->lsb_rad_per_s;
  int on_grid = 0;
  for (double v : y) on_grid += std::abs(v / lsb - std::nearbyint(v / lsb)) < 1e-9;
  EXPECT_LT(on_grid, 5);
  // The error is bounded by half an LSB: the dither is removed after rounding.
  SensorModel clean = model;
  clean.rate_quantizer.reset();
  const std::vector<double> x = clean.Generate(5, 0, 4096);
  for (std::size_t k = 0; k < y.size(); ++k) ASSERT_LE(std::abs(y[k] - x[k]), 0.5 * lsb * (1 + 1e-12));
}

}  // namespace
}  // namespace allanlab::sim
