// Starting estimates of diagnose's candidates (candidate_estimate.h) that the blind benchmark
// needed: the angle LSB when noise after the quantizer hides the value grid.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "estimators/fit/fit_avar_model.h"
#include "estimators/fit/noise_coefficient.h"
#include "experiments/diagnosis/candidate_estimate.h"
#include "experiments/diagnosis/diagnose.h"
#include "sim/sensor_model.h"
#include "sim/seeding.h"

namespace allanlab::experiments {
namespace {

// White rate noise whose angle crosses 3 LSBs (sd) per sample, so the quantization error is white
// with variance lsb^2/12 (its lag-1 correlation is ~e^{-2 pi^2 9}), then white noise added after
// the quantizer (1 % of the rate noise): no sample sits on the grid any more. The baseline's Q
// is then lsb / sqrt(12) within its fit sigma; the LSB estimate must lie within 5 of those
// sigmas (x sqrt(12)).
TEST(CandidateEstimateStatTest, AngleLsbWithoutAValueGrid) {
  constexpr double kFs = 100.0, kLsb = 1e-5;
  constexpr std::int64_t kN = 1 << 17;
  sim::SensorModel model;
  model.sample_clock = SampleClock::FromRateHz(kFs);
  const double arw = 3.0 * kLsb * std::sqrt(kFs);  // angle increment sd = arw sqrt(tau0)
  model.terms = {sim::WhiteRateNoise{arw}};
  model.angle_quantizer = sim::AngleQuantizer{kLsb};
  std::vector<double> y = model.Generate(5, 0, kN);
  sim::SensorModel after;
  after.sample_clock = SampleClock::FromRateHz(kFs);
  after.terms = {sim::WhiteRateNoise{0.01 * arw}};
  const std::vector<double> post = after.Generate(6, 0, kN);
  for (std::size_t k = 0; k < y.size(); ++k) y[k] += post[k];

  estimators::AvarCurve curve;
  std::string why;
  ASSERT_TRUE(RecordCurve(y, SampleClock::FromRateHz(kFs), &curve, &why)) << why;
  estimators::FitOptions fo;
  fo.method = estimators::FitMethod::kGls;
  estimators::FitSummary fit;
  ASSERT_TRUE(estimators::FitAvarModel(fo, curve, &fit)) << fit.message;
  const auto& q = fit.at(estimators::Coefficient::kQ);
  ASSERT_TRUE(q.fitted);
  sim::SensorModel baseline;
  baseline.sample_clock = SampleClock::FromRateHz(kFs);
  for (estimators::Coefficient c : estimators::kAllCoefficients) {
    if (fit.at(c).fitted && fit.at(c).value_si > 0.0) baseline.terms.push_back(estimators::TermFor(c, fit.at(c).value_si));
  }
  const auto base = baseline.ExpectedAvar(curve.m, {curve.num_samples, curve.estimator});
  EstimateInputs in{&curve, base, y, &baseline};
  const auto est = EstimateEffect(Effect::kAngleQuantization, in, &why);
  ASSERT_TRUE(est.has_value()) << why;
  EXPECT_NEAR(est->params.at("lsb_rad"), kLsb, 5.0 * q.sigma_si * std::sqrt(12.0));
}

}  // namespace
}  // namespace allanlab::experiments
