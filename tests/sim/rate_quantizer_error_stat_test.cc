// The rate quantizer on a band-limited signal whose noise per sample is below one LSB: its error
// is neither lsb^2/12 nor white, and the exact error autocovariance (output_quantizer.h) must
// reproduce the Monte Carlo mean of the overlapping AVAR where the white approximation does not.
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
  constexpr std::int64_t kN = 1 << 14;
  constexpr int kTrials = 200;
  const std::vector<std::int64_t> ms = testing_support::OctaveFactorsUpTo(kN / 8);
  const auto kind = AvarEstimatorKind::kOverlapping;
  const auto sample = testing_support::SimulateAvar(model, 17, kTrials, kN, ms, kind);
  const auto expected = model.ExpectedAvar(ms, {kN, kind});
  // The error is not Gaussian: the tolerance uses the Monte Carlo spread (z = 5).
  std::vector<double> sd;
  for (double v : sample.variance) sd.push_back(std::sqrt(v));
  EXPECT_TRUE(testing_support::MeanWithinTolerance(sample, expected, sd, ms));

  // The same check against signal + white lsb^2/12 must fail somewhere, or this test could not
  // tell the two theories apart.
  SensorModel unquantized = model;
  unquantized.rate_quantizer.reset();
  const auto signal = unquantized.ExpectedAvar(ms, {kN, kind});
  double worst_z = 0.0;
  for (std::size_t i = 0; i < ms.size(); ++i) {
    const double white = signal[i] + model.rate_quantizer->ApproximateAvar(ms[i]);
    worst_z = std::max(worst_z, std::abs(sample.mean[i] - white) / (sd[i] / std::sqrt(kTrials)));
  }
  EXPECT_GT(worst_z, 8.0) << "the white approximation is indistinguishable here";
}

}  // namespace
}  // namespace allanlab::sim
