// The profile ranges of a poor fit (docs/theory.md §4.7): where the model does not describe the
// curve the misfit sets chi2 under every covariance, and testing each held value under its own
// model's covariance moves the minimum with the held value. The fit then profiles with the weight
// it held, in the linear fit as in the band-limited one (SetFitProfileRanges, linear_profile.h).
// Record: from independent/, a generator written apart from sim/: white noise, flicker and a rate
// random walk like the ADIS16405's gyro behind a first-order 58 Hz low-pass at 100 Hz, 1 h, fitted
// without the band-limit, so that the IEEE terms alone fit it poorly (chi2 7657 on 48 dof).
// What it catches: the linear fit profiled each held value under its own covariance on a poor fit
// too, and the ranges collapsed to the value: here B 68.3 % and 95 % [0.3050, 0.3050] mrad/s, N
// 68.3 % [0.609047, 0.609048] mrad/sqrt(s) (ADIS16405 imu1 Gyro_Z with the band-limit off:
// N 2.597 [2.597, 2.597] deg/sqrt(h); Gyro_X: B 57.87 [57.87, 57.87] deg/h).
#include <gtest/gtest.h>

#include <cstdint>
#include <numbers>

#include "estimators/fit/fit_model.h"
#include "independent/generate.h"
#include "independent/recipe.h"

#include "tests/support/fit_curves.h"

namespace allanlab::estimators {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

TEST(PoorFitProfile, IntervalsOfTheLinearFitKeepTheirWidth) {
  independent::Recipe r;
  r.rate_hz = 100.0;
  r.noise.arw_rad_per_sqrt_s = 2.435 * kDeg / 60.0;
  r.noise.flicker_floor_rad_per_s = independent::FlickerFloorFromB(26.65 * kDeg / 3600.0);
  r.noise.rrw_rad_per_s_per_sqrt_s = 90.1 * kDeg / 3600.0 / 60.0;
  r.low_pass.design = independent::LowPassDesign::kFirstOrderImpulseInvariant;
  r.low_pass.cutoff_hz = 58.4;
  r.low_pass.oversampling = 8;
  r.low_pass.decimation = independent::Decimation::kAverage;
  const auto n = static_cast<std::int64_t>(3600.0 * r.rate_hz);
  const AvarCurve curve = testing_support::DenseCurveOf(independent::Generate(r, n, 1, 0), r.rate_hz);
  ModelFitOptions o;  // GLS on Q, N, B, K, R with the subset choice, band-limit off
  ModelFitSummary m;
  ASSERT_TRUE(FitModel(o, curve, &m)) << m.fit.message;
  ASSERT_TRUE(m.poor_fit) << "chi2 " << m.fit.chi2 << " on " << m.fit.dof << ": the record does not test a poor fit";
  int fitted = 0;
  for (Coefficient c : kAllCoefficients) {
    const CoefficientEstimate& e = m.fit.at(c);
    if (!e.fitted) continue;
    ++fitted;
    // A Gaussian range is 3.92 sigma wide at 95 % and 2 sigma at 68.3 %; half that is allowed.
    EXPECT_GT(e.interval95_si[1] - e.interval95_si[0], 2.0 * e.sigma_si) << CoefficientId(c) << ": the 95 % interval collapsed";
    EXPECT_GT(e.interval68_si[1] - e.interval68_si[0], 1.0 * e.sigma_si) << CoefficientId(c) << ": the 68.3 % interval collapsed";
    EXPECT_LT(e.interval68_si[0], e.value_si) << CoefficientId(c);
    EXPECT_GT(e.interval68_si[1], e.value_si) << CoefficientId(c);
  }
  EXPECT_GE(fitted, 2);
}

}  // namespace
}  // namespace allanlab::estimators
