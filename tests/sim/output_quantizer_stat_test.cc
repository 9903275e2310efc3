// Output quantizers: the angle quantizer with carry loses no angle, and both quantizers add the
// approximate Allan variance their headers state when the noise spans many LSBs.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/monte_carlo.h"

namespace allanlab::sim {
namespace {

TEST(AngleQuantizer, CarryKeepsTheIntegratedAngle) {
  SensorModel raw = testing_support::SingleTermModel(WhiteRateNoise{0.02}, 200.0);
  raw.bias_rad_per_s = 0.013;
  SensorModel quantized = raw;
  quantized.angle_quantizer = AngleQuantizer{1e-4};
  const auto y = raw.Generate(3, 0, 100000);
  const auto q = quantized.Generate(3, 0, 100000);
  long double angle = 0.0L, angle_q = 0.0L;
  for (std::size_t k = 0; k < y.size(); ++k) {
    angle += y[k] / 200.0L;
    angle_q += q[k] / 200.0L;
    // Every output is a whole number of LSBs per sample period, and the running angle never
    // drifts more than one LSB from the true one.
    const double counts = q[k] / 200.0 / 1e-4;  // output = counts * lsb / tau0
    ASSERT_NEAR(counts, std::round(counts), 1e-6);
    ASSERT_LE(std::abs(static_cast<double>(angle_q - angle)), 1e-4 * (1 + 1e-9));
  }
}

TEST(OutputQuantizers, AddTheirApproximateAvarForBusyNoise) {
  // Noise per sample 10x the LSB: the quantization error is close to uniform and white.
  constexpr std::int64_t kN = 1 << 14;
  constexpr int kTrials = 200;
  const double fs = 100.0, arw = 0.01;  // per-sample std 0.1 rad/s
  const std::vector<std::int64_t> ms = testing_support::OctaveFactorsUpTo(kN / 8);
  for (int which = 0; which < 2; ++which) {
    SensorModel model = testing_support::SingleTermModel(WhiteRateNoise{arw}, fs);
    if (which == 0) model.rate_quantizer = RateQuantizer{0.01};
    if (which == 1) model.angle_quantizer = AngleQuantizer{0.01 / fs};
    ASSERT_EQ(model.ExpectedAvarIsExact(), which == 1);
    const auto sample =
        testing_support::SimulateAvar(model, 8, kTrials, kN, ms, AvarEstimatorKind::kOverlapping);
    const auto expected = model.ExpectedAvar(ms, {kN, AvarEstimatorKind::kOverlapping});
    std::vector<double> sd;
    for (double v : sample.variance) sd.push_back(std::sqrt(v));  // non-Gaussian: MC spread
    EXPECT_TRUE(testing_support::MeanWithinTolerance(sample, expected, sd, ms))
        << (which == 0 ? "rate" : "angle") << " quantizer";
  }
}

}  // namespace
}  // namespace allanlab::sim
