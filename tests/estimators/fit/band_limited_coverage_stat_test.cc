// Coverage of the default fit's profile intervals under a fitted band-limit (FitModel with the
// band-limit detection on, as `allanlab fit`): K and B of a record like the ADIS16405's gyro
// (N 2.4 deg/sqrt(h), B 27 deg/h, K 90 deg/h/sqrt(h) behind a first-order 58 Hz low-pass at 100 Hz,
// the fit of a 10 000 s record's Gyro_X), 1 h long, from independent/, a generator written apart
// from sim/ (continuous-time averages, its own flicker and random numbers).
// Each count must lie in the two-sided acceptance band of Binomial(records, nominal) at level
// 1e-3 (tests/support/coverage_band.h): at 100 records [53, 83] at 68.3 % and [87, 100] at
// 95 %.
// What it catches: with the pilot fit's covariance held along the profile (the previous code) K's
// 68.3 % / 95 % intervals held the truth in 52 / 77 of these records (B's in 64 / 91); with each
// held value's own covariance (docs/theory.md §4.7) in 75 / 91 (B's 67 / 96). At 10 000 s, seeds
// 1-100: 56 / 74 before, 69 / 91 after.
// Q and R are 0 here. Without term selection in the band-limited fit (the previous code) they
// were reported by an upper limit in 53 and 61 of these records, and as a value with an interval
// in the others; with it (AIC's subset choice, as the plain fit) in 96 and 83, while K, B and N
// held the truth in 75 / 92, 64 / 94 and 64 / 94 (68.3 % / 95 %; before 75 / 91, 67 / 96, 60 / 95).
// Not asserted: a zero term kept by AIC with a 95 % interval that excludes 0, in 11 records here
// (5 without selection; 18 with the plain fit on the same records without the low-pass): R takes
// K's rise in the last taus, whose estimates are chi-square-like.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <string>
#include <utility>

#include "estimators/fit/fit_model.h"
#include "independent/generate.h"
#include "independent/recipe.h"

#include "tests/support/coverage_band.h"
#include "tests/support/fit_curves.h"

namespace allanlab::estimators {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kN = 2.435 * kDeg / 60.0, kB = 26.65 * kDeg / 3600.0, kK = 90.1 * kDeg / 3600.0 / 60.0;
constexpr double kFalseFail = 1e-3;  // per check

void ExpectCoverage(const std::string& what, int hits, int records, double nominal) {
  const auto [lo, hi] = testing_support::CoverageBand(records, nominal, kFalseFail, false);
  std::printf("%s: %d of %d (band %d..%d)\n", what.c_str(), hits, records, lo, hi);
  EXPECT_GE(hits, lo) << what;
  EXPECT_LE(hits, hi) << what;
}

// A term that is 0 is reported by its upper limit unless AIC's subset choice keeps it, which it
// does when the term lowers chi2 by more than 2: in 0.5 P(chi2_1 > 2) = 7.9 % of records with
// Gaussian estimates (linear_profile.h), more for R, pinned only by the last taus, whose
// estimates are chi-square-like with a few degrees of freedom. The count must reach the lower
// acceptance band of Binomial(records, 0.8): a zero term reported by a limit in four records of
// five at least.
void ExpectUpperLimitShare(const std::string& what, int limits, int records) {
  const auto [lo, hi] = testing_support::CoverageBand(records, 0.8, kFalseFail, true);
  std::printf("%s: %d of %d (at least %d)\n", what.c_str(), limits, records, lo);
  EXPECT_GE(limits, lo) << what;
}

// N, B and K (SI) at 100 Hz behind a low-pass of `design` at `cutoff_hz`, run at 8x and averaged
// to the output.
independent::Recipe BehindALowPass(double n, double b, double k, independent::LowPassDesign design, double cutoff_hz) {
  independent::Recipe r;
  r.rate_hz = 100.0;
  r.noise.arw_rad_per_sqrt_s = n;
  r.noise.flicker_floor_rad_per_s = independent::FlickerFloorFromB(b);
  r.noise.rrw_rad_per_s_per_sqrt_s = k;
  r.low_pass.design = design;
  r.low_pass.cutoff_hz = cutoff_hz;
  r.low_pass.oversampling = 8;
  r.low_pass.decimation = independent::Decimation::kAverage;
  return r;
}

TEST(BandLimitedCoverage, RandomWalkAndFlickerBehindALowPass) {
  const independent::Recipe r = BehindALowPass(kN, kB, kK, independent::LowPassDesign::kFirstOrderImpulseInvariant, 58.4);
  constexpr int kRecords = 100;
  constexpr double kDurationS = 3600.0;
  const auto n = static_cast<std::int64_t>(kDurationS * r.rate_hz);
  ModelFitOptions o;
  o.band_limit = BandLimitPolicy::kAuto;
  int band_limited = 0, k68 = 0, k95 = 0, b68 = 0, b95 = 0, n68 = 0, n95 = 0, q_limit = 0, r_limit = 0,
      zero_excluded = 0;
  for (int seed = 1; seed <= kRecords; ++seed) {
    const AvarCurve curve =
        testing_support::DenseCurveOf(independent::Generate(r, n, static_cast<std::uint64_t>(seed), 0), r.rate_hz);
    ModelFitSummary m;
    ASSERT_TRUE(FitModel(o, curve, &m)) << m.fit.message;
    band_limited += m.band_limited;
    const CoefficientEstimate& k = m.fit.at(Coefficient::kK);
    const CoefficientEstimate& b = m.fit.at(Coefficient::kB);
    k68 += k.interval68_si[0] <= kK && kK <= k.interval68_si[1];
    k95 += k.interval95_si[0] <= kK && kK <= k.interval95_si[1];
    b68 += b.interval68_si[0] <= kB && kB <= b.interval68_si[1];
    b95 += b.interval95_si[0] <= kB && kB <= b.interval95_si[1];
    const CoefficientEstimate& w = m.fit.at(Coefficient::kN);
    n68 += w.interval68_si[0] <= kN && kN <= w.interval68_si[1];
    n95 += w.interval95_si[0] <= kN && kN <= w.interval95_si[1];
    // Q and R are 0 in these records: a term the data do not hold is reported by an upper limit.
    for (auto [c, count] : {std::pair{Coefficient::kQ, &q_limit}, std::pair{Coefficient::kR, &r_limit}}) {
      const CoefficientEstimate& e = m.fit.at(c);
      *count += !e.fitted && e.has_upper_limit;
      zero_excluded += e.fitted && e.interval95_si[0] > 0.0;
    }
  }
  ASSERT_GE(band_limited, kRecords * 9 / 10) << "the band-limit is not found: these records do not test its fit";
  ExpectCoverage("K 68.3 % interval", k68, kRecords, 0.683);
  ExpectCoverage("K 95 % interval", k95, kRecords, 0.95);
  ExpectCoverage("B 68.3 % interval", b68, kRecords, 0.683);
  ExpectCoverage("B 95 % interval", b95, kRecords, 0.95);
  ExpectCoverage("N 68.3 % interval", n68, kRecords, 0.683);
  ExpectCoverage("N 95 % interval", n95, kRecords, 0.95);
  ExpectUpperLimitShare("Q (0) reported as an upper limit", q_limit, kRecords);
  ExpectUpperLimitShare("R (0) reported as an upper limit", r_limit, kRecords);
  std::printf("Q or R (0) reported with a 95 %% interval that excludes 0: %d of %d records\n", zero_excluded, kRecords);
}

// A 2nd-order 131 Hz low-pass (bilinear at 8x) averaged to a 100 Hz output, 1 h of N 0.15 deg/sqrt(h),
// B 0.75 deg/h and K 0.15 deg/h/sqrt(h) (the tactical_mems sensor read at 100 Hz): the cutoff lies
// above the output's Nyquist frequency and the curve barely pins it. On 14 of these 40 records the
// fit settles near 60-77 Hz with a quantization term Q of ~0.9 urad taking up the short taus (Q
// is 0 here), while a cutoff near 131 Hz with Q = 0 lies 1-4 above it in chi2; on the others
// near 120-140 Hz or 150-165 Hz without Q.
// Profiled with the cutoff free only to first order (the previous code), Q's 95 % interval held 0
// (or Q was given by an upper limit) in 28 of 40; profiled over the cutoff (parametric_fit.cc:
// CutoffAlternatives) in 32 of 40 (80 %, Wilson [65.2, 89.5] %): better, still short of 95 %.
// The cutoff's 95 % profile range holds 131 Hz in 22 of 40 (55 %, [39.8, 69.3] %), its
// +- 1.96 sigma in 12: the fitted cutoff of a bilinear filter read through sim/'s Butterworth
// shapes scatters between two branches (near 130 and near 157 Hz) wider than either profile.
// Asserted: the counts the cutoff profile reached, as a regression guard (fixed seeds); neither is
// nominal, which results/README.md and docs/theory.md §4.7 say.
TEST(BandLimitedCoverage, CutoffAboveNyquistIsProfiledOverTheCutoff) {
  constexpr double kNt = 0.15 * kDeg / 60.0, kBt = 0.7527 * kDeg / 3600.0, kKt = 0.15 * kDeg / 3600.0 / 60.0;
  constexpr double kCutoffHz = 131.0;
  const independent::Recipe r = BehindALowPass(kNt, kBt, kKt, independent::LowPassDesign::kSecondOrderBilinear, kCutoffHz);
  constexpr int kRecords = 40;
  const auto n = static_cast<std::int64_t>(3600.0 * r.rate_hz);
  ModelFitOptions o;
  o.band_limit = BandLimitPolicy::kAuto;
  int ranged = 0, cutoff_held = 0, sigma_held = 0, q_held = 0, n95 = 0;
  for (int seed = 1; seed <= kRecords; ++seed) {
    const AvarCurve curve =
        testing_support::DenseCurveOf(independent::Generate(r, n, static_cast<std::uint64_t>(seed), 0), r.rate_hz);
    ModelFitSummary m;
    ASSERT_TRUE(FitModel(o, curve, &m)) << m.fit.message;
    for (const ParametricEstimate& e : m.extra) {
      if (e.id != "bandwidth" || !e.fitted || e.interval95_si.empty()) continue;
      ++ranged;
      cutoff_held += e.interval95_si[0][0] <= kCutoffHz && kCutoffHz <= e.interval95_si[0][1];
      sigma_held += std::abs(e.value_si[0] - kCutoffHz) <= 1.96 * e.sigma_si[0];
    }
    const CoefficientEstimate& q = m.fit.at(Coefficient::kQ);
    q_held += !q.fitted || q.interval95_si[0] == 0.0;
    const CoefficientEstimate& w = m.fit.at(Coefficient::kN);
    n95 += w.interval95_si[0] <= kNt && kNt <= w.interval95_si[1];
  }
  std::printf("cutoff profiled on %d of %d records; 131 Hz inside its 95 %% range %d, inside +- 1.96 sigma %d\n",
              ranged, kRecords, cutoff_held, sigma_held);
  std::printf("Q (0) inside its 95 %% range or under its upper limit: %d of %d\n", q_held, kRecords);
  ASSERT_GE(ranged, kRecords * 9 / 10) << "the band-limit is not fitted: these records do not test its profile";
  EXPECT_GE(cutoff_held, 20) << "the cutoff's 95 % range (+- 1.96 sigma: " << sigma_held << ")";
  EXPECT_GE(q_held, 30) << "Q's 95 % range reaches 0 less often than profiled over the cutoff";
  ExpectCoverage("N 95 % interval", n95, kRecords, 0.95);
}

}  // namespace
}  // namespace allanlab::estimators
