// Coverage of the default fit's profile-likelihood intervals and upper limits (FitModel with its
// defaults: GLS on Q, N, B, K, R with the AIC subset choice, as `allanlab fit` and the "default"
// method of the coefficient_recovery tables) on records from independent/, a generator written
// apart from sim/ (continuous-time averages, its own flicker and random numbers).
//
// Records: 2 h at 10 Hz of N = 0.17 deg/sqrt(h) and K = 5 deg/h/sqrt(h), with and without
// B = 3 deg/h, where K is pinned only by the last few taus (EDF ~ 1-5) and is often reported by its
// 95 % upper limit. 10 Hz rather than 100 Hz keeps the test fast; K and B are set by the taus
// > 10 s, where the two rates give the same curve. Each count must lie in the two-sided acceptance
// band of Binomial(trials, nominal) at level 1e-3 (an upper limit: the band's lower end only, a
// conservative limit being allowed), so a calibrated method fails one check with probability
// 1e-3 and the test (12 checks) with at most 1.2e-2. At 160 trials the band is about nominal
// +- 12 points at 68.3 % and [88.8 %, 98.8 %] at 95 %.
// What it catches: with the GLS covariance held at the pilot fit along the profile (the previous
// code) the upper limit of K held the truth in 112 of 134 N + B + K records here (84 %) and in 4
// of 18 N + K records at seeds 1..200, and the 95 % interval of K in 139 of 160; both fail.
// The model is right, so POOR FIT must be as rare as its rule says (p < 1e-3): judged by the cost
// under the pilot's weight 25 of 200 white + random-walk records were called poor; judged under
// the model's own covariance but with the subsets scored under the pilot's weight, 6 of 200, 8 of
// 160 and 4 of 150 (docs/theory.md §4.8). And a term absent from the records must hold 0 in its
// 95 % range (or be given by its upper limit) as often as a 95 % range holds its truth.
// Not asserted: N's intervals on the records with flicker. independent/'s flicker is the mean of a
// continuous process over each sample, whose AVAR at m = 1 is 0.82 of the discrete shape the fit
// uses (0.98 at m = 4); N, fitted to 0.1 % there, feels it: its 95 % interval held the truth in
// 181 of 200 records (90.5 %, Wilson [85.6, 93.8] %), 191 of 200 on sim/'s records of the same
// model, 190 of 200 on these without flicker (asserted below).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "estimators/avar.h"
#include "estimators/fit/fit_model.h"
#include "independent/generate.h"
#include "independent/recipe.h"

#include "tests/support/coverage_band.h"
#include "tests/support/fit_curves.h"

namespace allanlab::estimators {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kFalseFail = 1e-3;  // per check

// Expects `hits` of `trials` inside the acceptance band of Binomial(trials, nominal).
void ExpectCoverage(const std::string& what, int hits, int trials, double nominal, bool lower_only) {
  const auto [lo, hi] = testing_support::CoverageBand(trials, nominal, kFalseFail, lower_only);
  std::printf("%s: %d of %d (band %d..%d)\n", what.c_str(), hits, trials, lo, hi);
  EXPECT_GE(hits, lo) << what << ": " << hits << " of " << trials << " (nominal " << nominal << ")";
  EXPECT_LE(hits, hi) << what << ": " << hits << " of " << trials << " (nominal " << nominal << ")";
}

struct Counts {
  int trials = 0;
  int in68[5] = {}, in95[5] = {}, limited[5] = {}, under[5] = {};
  int poor_fits = 0;  // records of the right model the fit called poor
  int zero_terms = 0, zero_held = 0;  // terms absent from the record; those whose 95 % range holds 0
};

// Fits `trials` records of the recipe (seeds 1..trials) with FitModel's defaults and counts, per
// coefficient, the intervals and upper limits that hold the truth (SI, indexed by Coefficient).
Counts FitRecords(const independent::Recipe& r, const double (&truth)[5], int trials) {
  constexpr double kDurationS = 7200.0;
  const auto n = static_cast<std::int64_t>(kDurationS * r.rate_hz);
  Counts c;
  c.trials = trials;
  for (int seed = 1; seed <= trials; ++seed) {
    const AvarCurve curve = testing_support::DenseCurveOf(independent::Generate(r, n, static_cast<std::uint64_t>(seed), 0), r.rate_hz);
    ModelFitSummary m;
    EXPECT_TRUE(FitModel(ModelFitOptions{}, curve, &m)) << m.fit.message;
    c.poor_fits += m.poor_fit;
    for (int i = 0; i < 5; ++i) {
      const CoefficientEstimate& e = m.fit.coefficients[i];
      if (truth[i] == 0.0) {
        ++c.zero_terms;
        c.zero_held += !e.fitted || e.interval95_si[0] == 0.0;
        continue;
      }
      EXPECT_TRUE(e.has_intervals) << i;
      if (e.fitted) {  // the reported value lies in its own intervals
        EXPECT_LE(e.interval68_si[0], e.value_si) << "seed " << seed << " term " << i;
        EXPECT_GE(e.interval68_si[1], e.value_si) << "seed " << seed << " term " << i;
      }
      c.in68[i] += e.interval68_si[0] <= truth[i] && truth[i] <= e.interval68_si[1];
      c.in95[i] += e.interval95_si[0] <= truth[i] && truth[i] <= e.interval95_si[1];
      if (e.has_upper_limit) {
        ++c.limited[i];
        c.under[i] += truth[i] <= e.upper_limit_si;
      }
    }
  }
  // The model is right, so the fit is called poor with probability kPoorFitP (fit_avar_model.h).
  const int most = testing_support::CoverageBand(trials, kPoorFitP, kFalseFail, false).hi;
  std::printf("POOR FIT on %d of %d records of the right model (at most %d)\n", c.poor_fits, trials, most);
  EXPECT_LE(c.poor_fits, most) << "the right model called a poor fit";
  // A term the record does not have: reported by an upper limit, or its 95 % range reaches 0.
  ExpectCoverage("absent terms' 95 % range holds 0", c.zero_held, c.zero_terms, 0.95, true);
  return c;
}

constexpr const char* kNames[5] = {"Q", "N", "B", "K", "R"};
constexpr double kN = 0.17 * kDeg / 60.0, kB = 3.0 * kDeg / 3600.0, kK = 5.0 * kDeg / 3600.0 / 60.0;

void ExpectIntervals(const Counts& c, int i) {
  ExpectCoverage(std::string(kNames[i]) + " 68.3 % interval", c.in68[i], c.trials, 0.683, false);
  ExpectCoverage(std::string(kNames[i]) + " 95 % interval", c.in95[i], c.trials, 0.95, false);
}

TEST(ProfileCoverage, FlickerAndRandomWalk) {
  const double truth[5] = {0.0, kN, kB, kK, 0.0};
  independent::Recipe r;
  r.rate_hz = 10.0;
  r.noise.arw_rad_per_sqrt_s = kN;
  r.noise.flicker_floor_rad_per_s = independent::FlickerFloorFromB(kB);
  r.noise.rrw_rad_per_s_per_sqrt_s = kK;
  const Counts c = FitRecords(r, truth, 160);
  ExpectIntervals(c, 2);
  ExpectIntervals(c, 3);
  // K is mostly not determined by 2 h: its upper limit is what these records test.
  ASSERT_GE(c.limited[3], c.trials / 2);
  ExpectCoverage("K 95 % upper limit", c.under[3], c.limited[3], 0.95, true);
}

TEST(ProfileCoverage, WhiteAndRandomWalk) {
  const double truth[5] = {0.0, kN, 0.0, kK, 0.0};
  independent::Recipe r;
  r.rate_hz = 10.0;
  r.noise.arw_rad_per_sqrt_s = kN;
  r.noise.rrw_rad_per_s_per_sqrt_s = kK;
  const Counts c = FitRecords(r, truth, 200);
  ExpectIntervals(c, 1);
  ExpectIntervals(c, 3);
  // Pooled with the records above: the limit must hold the truth whenever it is given.
  ExpectCoverage("K 95 % upper limit", c.under[3], std::max(c.limited[3], 1), 0.95, true);
}

// K far below what 2 h resolve (0.03 deg/h/sqrt(h) under N = 0.0267 deg/sqrt(h) and
// B = 0.18 deg/h, the mg25_mems sensor): K is pinned only by the last taus, whose estimates are
// chi-square-like with a few degrees of freedom, so the profile statistic at the truth is far from
// its Gaussian law (its 68.3 % quantile 0.03 against 0.227). With the Gaussian threshold K's
// 68.3 % interval held the truth in 166 of these 200 records (83.0 %, Wilson [77.2, 87.6] %), above
// the band; with the bootstrap-calibrated threshold (profile_calibration.h) in 151 (75.5 %).
TEST(ProfileCoverage, RandomWalkFarBelowResolution) {
  constexpr double kN2 = 0.0267 * kDeg / 60.0, kB2 = 0.1806 * kDeg / 3600.0, kK2 = 0.03 * kDeg / 3600.0 / 60.0;
  const double truth[5] = {0.0, kN2, kB2, kK2, 0.0};
  independent::Recipe r;
  r.rate_hz = 10.0;
  r.noise.arw_rad_per_sqrt_s = kN2;
  r.noise.flicker_floor_rad_per_s = independent::FlickerFloorFromB(kB2);
  r.noise.rrw_rad_per_s_per_sqrt_s = kK2;
  const Counts c = FitRecords(r, truth, 200);
  ExpectIntervals(c, 2);
  ExpectIntervals(c, 3);
}

// A flicker floor hidden by white noise until ~1 h (N, B and K of the rlg sensor): AIC often
// leaves B out, K takes the flicker's rise, and K's 95 % interval in {N, K} missed the truth
// (without the one-term superset in the hull, linear_profile.h: 130 of these 150 records held it,
// 86.7 %, Wilson [80.3, 91.2] %, below the band; with it 140 of 150).
TEST(ProfileCoverage, FlickerHiddenByWhiteNoise) {
  constexpr double kN3 = 0.0035 * kDeg / 60.0, kB3 = 0.00527 * kDeg / 3600.0, kK3 = 0.0005 * kDeg / 3600.0 / 60.0;
  const double truth[5] = {0.0, kN3, kB3, kK3, 0.0};
  independent::Recipe r;
  r.rate_hz = 10.0;
  r.noise.arw_rad_per_sqrt_s = kN3;
  r.noise.flicker_floor_rad_per_s = independent::FlickerFloorFromB(kB3);
  r.noise.rrw_rad_per_s_per_sqrt_s = kK3;
  const Counts c = FitRecords(r, truth, 150);
  ExpectIntervals(c, 3);
}

}  // namespace
}  // namespace allanlab::estimators
