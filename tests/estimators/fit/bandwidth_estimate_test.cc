// Bandwidth from the short-tau ADEV maximum: recovers fc from the exact curve of band-limited
// white noise, within its stated uncertainty on simulated records, and says why when the
// maximum is not visible.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "estimators/allan_variance.h"
#include "estimators/exact_avar_variance.h"
#include "estimators/fit/bandwidth_estimate.h"
#include "sim/sensor_model.h"

namespace allanlab::estimators {
namespace {

AvarCurve CurveOf(const sim::SensorModel& model, std::int64_t n, bool simulated, std::uint64_t seed) {
  AvarCurve c;
  c.sample_clock = model.sample_clock;
  c.num_samples = n;
  for (double x = 1; x <= 400; x *= std::pow(10.0, 1.0 / 20.0)) {
    const auto m = static_cast<std::int64_t>(std::llround(x));
    if (c.m.empty() || m > c.m.back()) c.m.push_back(m);
  }
  for (std::int64_t m : c.m) c.tau_s.push_back(m * c.sample_clock.period_s());
  const sim::RecordShape shape{n, sim::AvarEstimatorKind::kOverlapping};
  c.avar = simulated ? AllanVariance(model.Generate(seed, 0, n), c.m, shape.estimator)
                     : model.ExpectedAvar(c.m, shape);
  const auto r = model.GaussianAutocovariance(n + 2 * c.m.back());
  for (std::int64_t m : c.m) c.edf.push_back(ExactAvarMoments(r, m, shape).edf());
  return c;
}

sim::SensorModel BandLimitedWhite(sim::LowPassKind kind) {
  sim::SensorModel model;
  model.sample_clock = SampleClock::FromRateHz(10000.0);
  model.terms = {sim::WhiteRateNoise{1e-3}};
  model.band_limit = {kind, 100.0, 8, sim::OutputSampling::kAverage};
  return model;
}

TEST(BandwidthEstimate, RecoversCutoffFromExactCurve) {
  const auto first = EstimateBandwidth(CurveOf(BandLimitedWhite(sim::LowPassKind::kFirstOrder), 1 << 16, false, 0));
  ASSERT_TRUE(first.found) << first.note;
  EXPECT_NEAR(first.cutoff_first_order_hz, 100.0, 2.0);
  EXPECT_NEAR(first.time_constant_s, 1.0 / (2.0 * M_PI * 100.0), 3e-5);
  const auto bw2 = EstimateBandwidth(CurveOf(BandLimitedWhite(sim::LowPassKind::kButterworth2), 1 << 16, false, 0));
  ASSERT_TRUE(bw2.found) << bw2.note;
  EXPECT_NEAR(bw2.cutoff_butterworth2_hz, 100.0, 2.0);
}

TEST(BandwidthEstimate, SimulatedRecordsWithinThreeSigma) {
  const auto model = BandLimitedWhite(sim::LowPassKind::kFirstOrder);
  for (std::uint64_t seed : {1, 2, 3}) {
    const auto e = EstimateBandwidth(CurveOf(model, 1 << 18, true, seed));
    ASSERT_TRUE(e.found) << e.note;
    EXPECT_NEAR(e.cutoff_first_order_hz, 100.0, 3.0 * e.cutoff_first_order_sigma_hz + 2.0)
        << "seed " << seed << " sigma " << e.cutoff_first_order_sigma_hz;
  }
}

TEST(BandwidthEstimate, SaysWhyWhenNoPeak) {
  sim::SensorModel model;
  model.sample_clock = SampleClock::FromRateHz(100.0);
  model.terms = {sim::WhiteRateNoise{1e-3}};
  const auto e = EstimateBandwidth(CurveOf(model, 1 << 14, false, 0));
  EXPECT_FALSE(e.found);
  EXPECT_FALSE(e.note.empty());
}

}  // namespace
}  // namespace allanlab::estimators
