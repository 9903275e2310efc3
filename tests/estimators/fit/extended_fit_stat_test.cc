// The fit's band-limit and extended models on records from independent/ (a generator written apart
// from sim/ and from the fit: continuous-time processes averaged over each sample, its own digital
// low-pass designs and random numbers).
//  * A band-limited record without quantization: Q's 95 % profile range must hold 0. The profile
//    of a linear term that held the band-limit cutoff at its fit excluded it (tactical_mems at
//    100 Hz: Q = 0.50 urad, 95 % [0.47, 0.54], true 0); with the cutoff free to first order it
//    holds. Each record is a trial of a 95 % interval: the count must lie in the lower acceptance
//    band of Binomial(records, 0.95) at level 1e-3.
//  * Nested models in one metric: an extended model (the IEEE terms plus GM, H, BW or BW2) contains
//    the fit it extends, so its chi2 can never be higher; with the IEEE fit weighted by the exact
//    relative variances and the extended ones by the curve's EDFs it was (ADIS16405 Gyro_X: H+BW
//    chi2 130.8 against IEEE+BW 96.7).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>

#include "estimators/fit/fit_model.h"
#include "independent/generate.h"
#include "independent/recipe.h"

#include "tests/support/coverage_band.h"
#include "tests/support/independent_recipes.h"
#include "tests/support/fit_curves.h"

namespace allanlab::estimators {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kN = 0.2 * kDeg / 60.0, kB = 3.0 * kDeg / 3600.0, kK = 4.0 * kDeg / 3600.0 / 60.0;

independent::Recipe BandLimited() { return testing_support::BandLimitedMemsRecipe(); }

TEST(BandLimitProfile, QuantizationRangeHoldsZeroOnABandLimitedRecordWithoutIt) {
  constexpr int kRecords = 24;
  const independent::Recipe r = BandLimited();
  const auto n = static_cast<std::int64_t>(3600.0 * r.rate_hz);
  int holds = 0, band_limited = 0;
  for (int seed = 1; seed <= kRecords; ++seed) {
    const AvarCurve curve =
        testing_support::DenseCurveOf(independent::Generate(r, n, static_cast<std::uint64_t>(seed), 0), r.rate_hz);
    ModelFitOptions o;
    o.band_limit = BandLimitPolicy::kAuto;
    ModelFitSummary m;
    ASSERT_TRUE(FitModel(o, curve, &m)) << m.fit.message;
    band_limited += m.band_limited;
    const CoefficientEstimate& q = m.fit.at(Coefficient::kQ);
    const bool zero_inside = !q.fitted || q.interval95_si[0] == 0.0;
    holds += zero_inside;
    if (!zero_inside) {
      std::printf("seed %d: Q %.3g rad, 95 %% [%.3g, %.3g]\n", seed, q.value_si, q.interval95_si[0],
                  q.interval95_si[1]);
    }
  }
  const int lo = testing_support::CoverageBand(kRecords, 0.95, 1e-3, true).lo;
  std::printf("Q's 95 %% range holds 0 in %d of %d records (band >= %d); band-limit found in %d\n", holds,
              kRecords, lo, band_limited);
  EXPECT_GE(band_limited, kRecords / 2) << "the records are not band-limited enough to test this";
  EXPECT_GE(holds, lo);
}

TEST(ExtendedFit, ANestedExtendedModelNeverFitsWorseThanTheFitItExtends) {
  // Records the IEEE terms fit poorly, so every extended model is tried: a Gauss-Markov bump, a
  // sinusoid, and the band-limited record.
  independent::Recipe gm;
  gm.rate_hz = 50.0;
  gm.noise.arw_rad_per_sqrt_s = kN;
  gm.noise.flicker_floor_rad_per_s = independent::FlickerFloorFromB(kB);
  gm.gauss_markov = independent::GaussMarkov{20.0 * kDeg / 3600.0, 5.0};
  independent::Recipe sine = gm;
  sine.gauss_markov.reset();
  sine.sinusoid = independent::Sinusoid{40.0 * kDeg / 3600.0, 1.3, std::nullopt};
  const independent::Recipe recipes[] = {gm, sine, BandLimited()};
  int tried = 0;
  for (const independent::Recipe& r : recipes) {
    const auto n = static_cast<std::int64_t>(3600.0 * r.rate_hz);
    const AvarCurve curve = testing_support::DenseCurveOf(independent::Generate(r, n, 11, 0), r.rate_hz);
    ModelFitOptions o;
    o.band_limit = BandLimitPolicy::kAuto;
    o.try_extended_on_poor_fit = true;
    ModelFitSummary m;
    ASSERT_TRUE(FitModel(o, curve, &m)) << m.fit.message;
    std::printf("record %d: chi2 %.4g on %d dof%s\n", int(&r - recipes), m.poor_fit ? m.poor_chi2 : m.fit.chi2,
                m.poor_fit ? m.poor_dof : m.fit.dof, m.poor_fit ? " (poor fit)" : "");
    if (!m.poor_fit) continue;
    for (const ExtendedFit& x : m.extended) {
      ++tried;
      std::printf("%s: chi2 %.4g against %.4g\n", x.name.c_str(), x.fit.chi2, m.poor_chi2);
      EXPECT_LE(x.fit.chi2, m.poor_chi2 * (1.0 + 1e-6) + 1e-6) << x.name;
    }
  }
  EXPECT_GE(tried, 4) << "too few extended models tried for the test to say anything";
}

}  // namespace
}  // namespace allanlab::estimators
