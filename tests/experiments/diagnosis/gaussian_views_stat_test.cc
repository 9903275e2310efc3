// The views' theory for a Gaussian model (gaussian_views.h) on records it did not make: white
// noise, flicker and a rate random walk from independent/ (spectral flicker, random walk
// averaged over each sample interval, its own random numbers), against the sim/ model with the
// same coefficients. Under the model each point's z should be standard normal, tails included:
// the test counts, per point, the records beyond the 1 % quantile on either side.
//
// Why the tails: the last hadamard points have a few EDF, where ln OHVAR has a long lower tail,
// and the kurtosis of a few hundred increments is skewed to the right (0.87 at 256). A normal
// reading of either (what a mean and sd of the statistic give) puts several per cent beyond a
// 1 % quantile at those points, which the bound below does not allow.
// Measured (seed 9100, expected 20 per tail): kurtosis 12-28; psd 11-33 (the first band 11
// below, 29 above); halves 6-29; hadamard 8-32, except the last point (m = 4096, EDF 6.2) with 2
// below and 30 above. There the mean (1.029 +- 0.013 of the theory) and the EDF (6.22 observed)
// agree; the estimate is a weighted sum of chi2_1 terms, more skewed than the chi2 of the same
// mean and variance, so the chi-square reading is conservative below the model and about 1.5x
// liberal above it at EDF ~ 6. The dynamic view: see the bound below.
// Before the first band had its exact EDF, Welch's rule put 44 above (the test failed).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "experiments/diagnosis/gap.h"
#include "experiments/diagnosis/gaussian_views.h"
#include "experiments/diagnosis/record_views.h"
#include "independent/generate.h"
#include "independent/recipe.h"
#include "experiments/diagnosis/warmup_drift_views.h"
#include "sim/exponential_drift.h"
#include "sim/flicker_noise.h"
#include "sim/output_quantizer.h"
#include "sim/random_walk_rate.h"
#include "sim/sensor_model.h"
#include "sim/white_rate_noise.h"

namespace allanlab::experiments {
namespace {

constexpr double kArw = 5.8e-5;    // rad/sqrt(s): 0.2 deg/sqrt(h)
constexpr double kB = 2.4e-5;      // rad/s: 5 deg/h
constexpr double kRrw = 2.4e-7;    // rad/s/sqrt(s): 3 deg/h/sqrt(h)
constexpr std::int64_t kSamples = 32768;
constexpr int kRecords = 2000;
constexpr double kTail = 0.01;
constexpr double kZTail = 2.3263478740408408;  // Phi^-1(0.99)

struct TailCounts {
  View view;
  std::size_t index;
  double x;
  int below = 0, above = 0;
  double lower = 0.0, upper = 0.0;  // the observed values whose z is -kZTail and +kZTail
};

// The observed value at which point i's z reaches `target` (z rises with the observed value in
// every view), by bisection from the model's value: counting records beyond the two such values
// counts |z| > kZTail with two law evaluations per point instead of one per record (a dynamic
// point with unequal windows costs milliseconds). -inf when no value reaches it (a range cannot
// be negative).
double ObservedAtZ(View view, const GaussianViewTheory& t, std::size_t i, double target) {
  double expected = 0.0;
  GaussianViewZ(view, t, 0.0, i, &expected);
  const bool log_scale = view == View::kHadamard || view == View::kPsd;
  const double centre = log_scale ? std::log(expected) : expected;
  auto z = [&](double x) {
    double ignored = 0.0;
    return GaussianViewZ(view, t, x, i, &ignored);
  };
  const double direction = target > 0.0 ? 1.0 : -1.0;
  double near = centre, far = centre, step = 0.05;
  for (int k = 0; k < 60; ++k) {
    far = centre + direction * step;
    if (view == View::kDynamic && far < 0.0) {
      far = 0.0;
      if (!(z(far) <= target)) return -std::numeric_limits<double>::infinity();
      break;
    }
    if (direction * (z(far) - target) >= 0.0) break;
    near = far;
    step *= 2.0;
  }
  for (int k = 0; k < 50; ++k) {
    const double mid = 0.5 * (near + far);
    if (direction * (z(mid) - target) >= 0.0) far = mid; else near = mid;
  }
  return 0.5 * (near + far);
}

// Per point of every view beyond OAVAR, how many of `records` records of `recipe` fall beyond the
// 1 % quantile on either side under the theory of `model`.
std::vector<TailCounts> CountTails(const sim::SensorModel& model, const independent::Recipe& recipe, int records,
                                   std::uint64_t seed) {
  std::vector<std::int64_t> oavar_m;
  for (std::int64_t m = 1; m <= kSamples / 2; m *= 2) oavar_m.push_back(m);
  const ViewLayout layout = MakeViewLayout(model.sample_clock, kSamples, oavar_m);
  const GaussianViewTheory theory = ExactGaussianViews(model, layout);
  EXPECT_FALSE(theory.empty());
  if (theory.empty()) return {};
  const std::vector<View> views = {View::kHadamard, View::kHalves, View::kDynamic, View::kPsd, View::kKurtosis};
  std::vector<TailCounts> points;
  for (View v : views) {
    const std::vector<double> axis = layout.Axis(v);
    for (std::size_t i = 0; i < axis.size(); ++i) points.push_back({v, i, axis[i]});
  }
  EXPECT_GT(layout.Size(View::kPsd), 0u);
  for (TailCounts& p : points) {
    p.lower = ObservedAtZ(p.view, theory, p.index, -kZTail);
    p.upper = ObservedAtZ(p.view, theory, p.index, kZTail);
  }
  for (int r = 0; r < records; ++r) {
    const std::vector<double> record = independent::Generate(recipe, kSamples, seed, static_cast<std::uint64_t>(r));
    ViewValues values;
    std::string why;
    if (!ComputeViews(layout, record, &values, &why, ViewSetOf(views))) {
      ADD_FAILURE() << why;
      return {};
    }
    for (TailCounts& p : points) {
      const double x = values[static_cast<int>(p.view)][p.index];
      EXPECT_TRUE(std::isfinite(x)) << ViewId(p.view) << " at " << p.x;
      p.below += x < p.lower;
      p.above += x > p.upper;
    }
  }
  return points;
}

// Each count ~ Binomial(records, 0.01). Bound: 4.5 sd (P ~ 7e-6 per count, about 120 counts).
// Too many beyond a quantile is a false alarm the level does not allow, checked everywhere; too
// few is lost power, checked except where the reading is conservative by design: the dynamic
// view's windows (and the halves) are taken as independent, and at long taus a random walk's
// windows correlate, which narrows the range (measured: the dynamic view at 5.12 s has 0 of 2000
// above the 1 % quantile).
void ExpectStandardTails(const std::vector<TailCounts>& points, int records) {
  const double expected = records * kTail;
  const double bound = 4.5 * std::sqrt(expected * (1.0 - kTail));
  for (const TailCounts& p : points) {
    std::printf("%s at %g: below %d, above %d of %d (expected %.0f each)\n", std::string(ViewId(p.view)).c_str(), p.x,
                p.below, p.above, records, expected);
    EXPECT_LE(p.below, expected + bound) << ViewId(p.view) << " at " << p.x << ": lower tail";
    EXPECT_LE(p.above, expected + bound) << ViewId(p.view) << " at " << p.x << ": upper tail";
    if (p.view == View::kDynamic) continue;
    EXPECT_GE(p.below, expected - bound) << ViewId(p.view) << " at " << p.x << ": lower tail";
    EXPECT_GE(p.above, expected - bound) << ViewId(p.view) << " at " << p.x << ": upper tail";
  }
}

sim::SensorModel NoiseModel() {
  sim::SensorModel model;
  model.sample_clock = SampleClock::FromRateHz(100.0);
  model.terms.push_back(sim::WhiteRateNoise{.arw_rad_per_sqrt_s = kArw});
  model.terms.push_back(sim::FlickerNoise{.bias_instability_rad_per_s = kB});
  model.terms.push_back(sim::RandomWalkRate{.rrw_rad_per_s_per_sqrt_s = kRrw});
  return model;
}

independent::Recipe NoiseRecipe() {
  independent::Recipe recipe;
  recipe.rate_hz = 100.0;
  recipe.noise.arw_rad_per_sqrt_s = kArw;
  recipe.noise.flicker_floor_rad_per_s = independent::FlickerFloorFromB(kB);
  recipe.noise.rrw_rad_per_s_per_sqrt_s = kRrw;
  return recipe;
}

TEST(GaussianViewsStatTest, EveryViewsZIsStandardNormalInBothTails) {
  ExpectStandardTails(CountTails(NoiseModel(), NoiseRecipe(), kRecords, 9100), kRecords);
}

// A fine output quantizer (IsGaussianModel): a rate LSB of 0.6 of the white noise's per-sample
// sd, its error 3 % of the first differences' variance, just inside the bound at this length
// (4.7 %). The independent generator rounds the rate with no offset (the grid centred on the
// bias); the model's quantizer averages over the offset, which a fine LSB makes moot.
// The test sees the quantizer: with the model's quantizer left out (the theory of the unquantized
// noise) 19 points fail, hadamard at 0.01 s with 651 of 1000 records above the 1 % quantile.
TEST(GaussianViewsStatTest, AFineQuantizersViewsFollowTheGaussianTheory) {
  constexpr double kLsb = 3.5e-4;  // rad/s; the white noise's sd per sample is kArw sqrt(100 Hz) = 5.8e-4
  sim::SensorModel model = NoiseModel();
  model.rate_quantizer = sim::RateQuantizer{.lsb_rad_per_s = kLsb, .random_offset = true};
  // The share from the white parts alone: the error's first differences 2 lsb^2/12 against the
  // white noise's 2 N^2 fs. The flicker adds about B^2 / (2 N^2 fs) = 8.6e-4 of the latter to the
  // differences (the random walk K^2 tau0 / (2 N^2 fs) < 1e-9), which lowers the share by as much
  // (1.06e-3 measured); the tolerance is twice that.
  const double error = kLsb * kLsb / 6.0;
  const double expected_share = error / (error + 2.0 * kArw * kArw * 100.0);
  EXPECT_NEAR(QuantizerShareOfDifferences(model), expected_share, 2e-3 * expected_share);
  ASSERT_TRUE(IsGaussianModel(model, kSamples));
  independent::Recipe recipe = NoiseRecipe();
  recipe.rate_quantizer = independent::RateQuantizer{.lsb_rad_per_s = kLsb};
  constexpr int kQuantizedRecords = 1000;
  ExpectStandardTails(CountTails(model, recipe, kQuantizedRecords, 9200), kQuantizedRecords);
}

// Where the quantizer is coarse for the record's length, the views stay Monte Carlo: the same LSB
// on 1e6 samples (bound 2 %), and an LSB of twice the per-sample sd on any length.
TEST(GaussianViewsStatTest, ACoarseQuantizerIsNotGaussian) {
  sim::SensorModel model = NoiseModel();
  model.rate_quantizer = sim::RateQuantizer{.lsb_rad_per_s = 3.5e-4, .random_offset = true};
  EXPECT_FALSE(IsGaussianModel(model, 1000000));
  model.rate_quantizer->lsb_rad_per_s = 1.2e-3;
  EXPECT_FALSE(IsGaussianModel(model, 4096));
  model.rate_quantizer.reset();
  model.angle_quantizer = sim::AngleQuantizer{.lsb_rad = 1e-7};  // 1e-5 rad/s per sample at 100 Hz: fine
  EXPECT_LT(QuantizerShareOfDifferences(model), 0.001);
  EXPECT_TRUE(IsGaussianModel(model, 1000000));
}

// A warm-up drift on the Gaussian noise (warmup_drift_views.h): 2e-3 rad/s (413 deg/h) settling
// with a 30 s time constant over the 328 s records. The independent generator averages the
// exponential over each sample interval; the model's is point-sampled, so its amplitude is the
// interval mean's at the first sample.
// The test sees the drift: with the theory of the noise alone (the drift's share left out) 13
// points fail, 1000 of 1000 records above the 1 % quantile at the last three halves points, the
// last two hadamard points and the first PSD band, 826 at the dynamic view's 2.56 s (10 with it);
// at 5e-4 rad/s and 60 s, 4 points still fail without it.
TEST(GaussianViewsStatTest, AWarmUpDriftsViewsFollowTheTheory) {
  constexpr double kAmplitude = 2e-3, kTimeConstant = 30.0;
  const double x = 0.01 / kTimeConstant;
  sim::SensorModel model = NoiseModel();
  model.terms.push_back(sim::ExponentialDrift{.amplitude_rad_per_s = kAmplitude * -std::expm1(-x) / x,
                                              .time_constant_s = kTimeConstant});
  ASSERT_FALSE(IsGaussianModel(model, kSamples));
  sim::SensorModel gaussian_part;
  ASSERT_TRUE(SplitWarmupDrift(model, kSamples, &gaussian_part).has_value());
  independent::Recipe recipe = NoiseRecipe();
  recipe.warmup_drift = independent::WarmupDrift{.amplitude_rad_per_s = kAmplitude, .time_constant_s = kTimeConstant};
  constexpr int kDriftRecords = 1000;
  ExpectStandardTails(CountTails(model, recipe, kDriftRecords, 9300), kDriftRecords);
}

}  // namespace
}  // namespace allanlab::experiments
