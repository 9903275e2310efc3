// The block-mean views (experiments/diagnosis/block_means.h) on records from the independent
// generator (independent/: continuous-time processes averaged over each sample, its own random
// numbers and flicker), never from sim/:
//   * false alarms: controls judged against their true model, each view on its own at the
//     default level (Bonferroni over its own points, alpha = 5 %); the rate's Wilson 95 % upper
//     bound must be <= 8 %. On the old code (no such views) the test has nothing to count.
//   * the records a free rate random walk hid from every other view (a 15 deg/h step at 2500 s, a
//     60 deg/h warm-up drift with tw 600 s, a 4 deg/h telegraph with 60 s dwell, on N 0.15
//     deg/sqrt(h), B 3 deg/h, K 3 deg/h/sqrt(h), 2.5 h at 100 Hz) are flagged by them, the step
//     located within one block of its time.
// Seeds are fixed, so the outcome is deterministic; the rate check fails spuriously with
// probability < 2.5 % if the true rate is 5 % (Wilson at 95 %, one-sided).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <span>
#include <sstream>
#include <string>
#include <variant>
#include <vector>

#include <boost/math/distributions/normal.hpp>

#include "experiments/aggregate.h"
#include "experiments/diagnosis/baseline.h"
#include "experiments/diagnosis/block_means.h"
#include "experiments/diagnosis/diagnose.h"
#include "independent/generate.h"
#include "sim/sensor_model.h"
#include "tests/support/diagnosis_record.h"

namespace allanlab::experiments {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kDegPerHour = kDeg / 3600.0;

struct Sensor {
  double n_deg_per_sqrt_h = 0.15, b_deg_per_h = 3.0, k_deg_per_h_per_sqrt_h = 3.0, rate_hz = 100.0;
};

independent::Recipe RecipeOf(const Sensor& s) {
  independent::Recipe r;
  r.rate_hz = s.rate_hz;
  r.noise.arw_rad_per_sqrt_s = s.n_deg_per_sqrt_h * kDeg / 60.0;
  r.noise.flicker_floor_rad_per_s = 0.6643 * s.b_deg_per_h * kDegPerHour;  // recipe.h: the Allan floor
  r.noise.rrw_rad_per_s_per_sqrt_s = s.k_deg_per_h_per_sqrt_h * kDegPerHour / 60.0;
  return r;
}

sim::SensorModel ModelOf(const Sensor& s) {
  sim::SensorModel m;
  m.sample_clock = SampleClock::FromRateHz(s.rate_hz);
  sim::WhiteRateNoise white;
  white.arw_rad_per_sqrt_s = s.n_deg_per_sqrt_h * kDeg / 60.0;
  sim::FlickerNoise flicker;
  flicker.bias_instability_rad_per_s = s.b_deg_per_h * kDegPerHour;
  sim::RandomWalkRate walk;
  walk.rrw_rad_per_s_per_sqrt_s = s.k_deg_per_h_per_sqrt_h * kDegPerHour / 60.0;
  m.terms = {white, flicker, walk};
  return m;
}

double OwnThreshold(double alpha, int points) {
  return -boost::math::quantile(boost::math::normal(), alpha / (2.0 * points));
}

double MaxAbsZ(const ViewResiduals& v) {
  double z = 0.0;
  for (double x : v.z) z = std::max(z, std::abs(x));
  return z;
}

TEST(BlockMeansStat, FalseAlarmRateUnderTheModel) {
  const Sensor sensor;
  const independent::Recipe recipe = RecipeOf(sensor);
  const sim::SensorModel model = ModelOf(sensor);
  constexpr int kTrials = 400;
  constexpr std::int64_t kSamples = 1 << 16;  // 11 min at 100 Hz
  const std::vector<int> counts = BlockMeanCounts(kSamples);
  int alarms[2] = {0, 0};
  for (int t = 0; t < kTrials; ++t) {
    const std::vector<double> y = independent::Generate(recipe, kSamples, 9100 + t, 0);
    ViewResiduals change, trend;
    BlockMeanResiduals(y, 1.0 / sensor.rate_hz, counts, model, 0.0, &change, &trend);
    const double z = OwnThreshold(0.05, static_cast<int>(counts.size()));
    alarms[0] += MaxAbsZ(change) > z;
    alarms[1] += MaxAbsZ(trend) > z;
  }
  for (int v = 0; v < 2; ++v) {
    const RateInterval ci = WilsonInterval(static_cast<double>(alarms[v]) / kTrials, kTrials);
    RecordProperty(v == 0 ? "change_point_alarms" : "trend_alarms", alarms[v]);
    std::printf("%s: %d / %d false alarms, Wilson 95 %% [%.4f, %.4f]\n", v == 0 ? "change_point" : "trend",
                alarms[v], kTrials, ci.low, ci.high);
    EXPECT_LE(ci.high, 0.08) << (v == 0 ? "change_point" : "trend") << " " << alarms[v] << " / " << kTrials;
  }
}

DiagnosisSummary DiagnoseIndependent(const independent::Recipe& recipe, std::int64_t n, std::uint64_t seed) {
  return testing::DiagnoseIndependentRecord(recipe, n, seed, testing::UserModelNBK());
}

std::string Regions(const DiagnosisSummary& s) {
  std::ostringstream out;
  for (const GapRegion& r : s.regions) {
    out << " " << ViewId(r.view) << " " << r.x_min << ".." << r.x_max << " |z| " << r.max_abs_z << " t "
        << r.time_s << ";";
  }
  return out.str();
}

const GapRegion* RegionOf(const DiagnosisSummary& s, View view) {
  for (const GapRegion& r : s.regions) {
    if (r.view == view) return &r;
  }
  return nullptr;
}

const CandidateResult* CandidateOf(const DiagnosisSummary& s, const std::string& id) {
  for (const CandidateResult& c : s.candidates) {
    if (c.id() == id) return &c;
  }
  return nullptr;
}

const std::int64_t kIssueSamples = 900000;  // 2.5 h at 100 Hz

// N, B and K fitted to the record's Allan curve, as diagnose's baseline (`--model N,B,K`), with
// the largest K the fit allows (what the change-point view profiles K up to) and whether the fit
// kept K.
struct Fitted {
  sim::SensorModel model;
  double k_bound = 0.0;
  bool k_kept = false;
};

Fitted FittedBaseline(std::span<const double> y, double rate_hz) {
  estimators::AvarCurve curve;
  std::string why, note;
  const SampleClock clock = SampleClock::FromRateHz(rate_hz);
  EXPECT_TRUE(RecordCurve(y, clock, &curve, &why)) << why;
  DiagnoseOptions options;
  options.terms = {estimators::Coefficient::kN, estimators::Coefficient::kB, estimators::Coefficient::kK};
  detail::BaselineSpec spec;
  estimators::FitSummary fit;
  EXPECT_TRUE(detail::FitBaseline(options, curve, &spec, &fit, &note, &why)) << why;
  return {spec.Model(fit, clock), detail::RandomWalkBound(spec, fit), fit.at(estimators::Coefficient::kK).fitted};
}

// The fitted K's value in the model [rad/s/sqrt(s)] (0 when the fit left K out).
double ModelK(const sim::SensorModel& m) {
  for (const sim::NoiseTerm& t : m.terms) {
    if (const auto* k = std::get_if<sim::RandomWalkRate>(&t)) return k->rrw_rad_per_s_per_sqrt_s;
  }
  return 0.0;
}

// A step at 2500 s (2.5 h at 100 Hz, N 0.15 deg/sqrt(h), B 3 deg/h, K 3 deg/h/sqrt(h)) against
// the baseline fitted to each record: the step raises the long taus, and the free K comes out
// 9-16 deg/h/sqrt(h) on most records (on the rest the fit leaves K out, its upper limit 12-15).
// Against that random walk held, the jump looked ordinary; with K profiled out of the change-point
// statistic (profiled_step.h) between 0 and the fit's upper bound, it is judged against the random
// walk the other block-mean differences allow. Over 20 fixed seeds, beyond the record's threshold
// (3.58, that of diagnose on these records):
//   * 15 deg/h, the detection limit: 10 of 20 flagged (19 of 40 over seeds 5000-5039, 47.5 %
//     [32.9, 62.5] %). On the 13 records where the fit kept K: 8 with K profiled, 3 with K held
//     at its fitted value, and K profiled never loses one K held flags. Where the fit left K out
//     the old statistic, K held at 0, flagged 7 of 7 (27 of 40 in all over 40 seeds), but that judgement
//     is what raised false alarms to 24.5 % on controls (below): a step of this size is not told
//     from the random walk such a record cannot exclude. The bound, 7, is what a rate of 50 %
//     undershoots with probability 0.06 (binomial).
//   * 20 deg/h: 17 of 20 (37 of 40 over seeds 5000-5039, 92.5 % [80.1, 97.4] %; the old statistic
//     36 of 40). The bound, 16, is what a detection rate of 90 % undershoots with probability
//     0.04 (binomial).
int StepsFlagged(double size_deg_per_h, int seeds, int* kept, int* kept_held, int* kept_profiled) {
  constexpr double kRecordThreshold = 3.58;
  independent::Recipe r = RecipeOf(Sensor{});
  r.bias_step = independent::BiasStep{size_deg_per_h * kDegPerHour, 2500.0};
  const std::vector<int> counts = BlockMeanCounts(kIssueSamples);
  int flagged = 0;
  *kept = *kept_held = *kept_profiled = 0;
  for (int seed = 5000; seed < 5000 + seeds; ++seed) {
    const std::vector<double> y = independent::Generate(r, kIssueSamples, seed, 0);
    const Fitted f = FittedBaseline(y, r.rate_hz);
    ViewResiduals held_k, free_k, trend;
    BlockMeanResiduals(y, 1.0 / r.rate_hz, counts, f.model, f.k_bound, &free_k, &trend);
    const bool is = MaxAbsZ(free_k) > kRecordThreshold;
    flagged += is;
    if (!f.k_kept) continue;
    BlockMeanResiduals(y, 1.0 / r.rate_hz, counts, f.model, 0.0, &held_k, &trend);
    const bool was = MaxAbsZ(held_k) > kRecordThreshold;
    ++*kept;
    *kept_held += was;
    *kept_profiled += is;
    EXPECT_TRUE(is || !was) << "seed " << seed << ": |z| " << MaxAbsZ(held_k) << " -> " << MaxAbsZ(free_k);
  }
  return flagged;
}

TEST(BlockMeansStat, AStepAFreeKAbsorbedIsFlaggedWithKProfiled) {
  int kept = 0, held = 0, profiled = 0;
  const int at15 = StepsFlagged(15.0, 20, &kept, &held, &profiled);
  std::printf("15 deg/h step flagged %d / 20; where the fit kept K (%d): K held %d, K profiled %d\n", at15, kept, held,
              profiled);
  EXPECT_GT(profiled, held);
  EXPECT_GE(at15, 7);
  const int at20 = StepsFlagged(20.0, 20, &kept, &held, &profiled);
  std::printf("20 deg/h step flagged %d / 20\n", at20);
  EXPECT_GE(at20, 16);
}

// Controls (43 min, N 0.15 deg/sqrt(h), B 3 deg/h, K 10 deg/h/sqrt(h)) against the baseline
// fitted to each (`--model N,B,K`): the fit leaves K out of many of them (183 of 200 when the
// subsets were scored under the pilot's weight, about half since they are scored by the
// likelihood, linear_profile.h), and with K held at 0 the change-point view read the random walk's
// wander as steps: 49 / 200 = 24.5 %
// [19.1, 30.9] % false alarms. With K profiled up to the fit's upper limit (the random walk the
// record cannot exclude) and the statistic's null drawn there: 4 / 200 = 2.0 % [0.8, 5.0] %. The
// change-point view on its own (Bonferroni over its 3 points, alpha 5 %); the Wilson 95 % upper
// bound must be <= 8 %.
TEST(BlockMeansStat, ControlsWhoseFitLeavesKOutRaiseFewAlarms) {
  Sensor sensor;
  sensor.k_deg_per_h_per_sqrt_h = 10.0;
  const independent::Recipe recipe = RecipeOf(sensor);
  constexpr int kTrials = 200;
  constexpr std::int64_t kSamples = 1 << 18;
  const std::vector<int> counts = BlockMeanCounts(kSamples);
  int alarms = 0, k_left_out = 0;
  for (int t = 0; t < kTrials; ++t) {
    const std::vector<double> y = independent::Generate(recipe, kSamples, 9700 + t, 0);
    const Fitted f = FittedBaseline(y, recipe.rate_hz);
    k_left_out += !f.k_kept;
    EXPECT_GE(f.k_bound, ModelK(f.model));
    ViewResiduals change, trend;
    BlockMeanResiduals(y, 1.0 / recipe.rate_hz, counts, f.model, f.k_bound, &change, &trend);
    alarms += MaxAbsZ(change) > OwnThreshold(0.05, static_cast<int>(counts.size()));
  }
  const RateInterval ci = WilsonInterval(static_cast<double>(alarms) / kTrials, kTrials);
  std::printf("fitted baseline, K left out on %d / %d: change_point %d false alarms, Wilson 95 %% [%.4f, %.4f]\n",
              k_left_out, kTrials, alarms, ci.low, ci.high);
  EXPECT_GE(k_left_out, kTrials / 4);  // the case this test is about
  EXPECT_LE(ci.high, 0.08) << alarms << " / " << kTrials;
}

// Controls (43 min, K 10 deg/h/sqrt(h)) against their true model with K profiled between 0 and
// its true value: the change-point view on its own (Bonferroni over its 3 points, alpha 5 %)
// flags at most the stated rate against the profiled statistic's own null (profiled_step.h; the
// held-K law did not serve: 24 / 400 = 6.0 % [4.1, 8.8] %, held K 14 / 400). 400 records; the
// Wilson 95 % upper bound must be <= 8 % (as the held statistic's own check above).
TEST(BlockMeansStat, ProfiledChangePointFalseAlarmRate) {
  Sensor sensor;
  sensor.k_deg_per_h_per_sqrt_h = 10.0;
  const independent::Recipe recipe = RecipeOf(sensor);
  const sim::SensorModel model = ModelOf(sensor);
  constexpr int kTrials = 400;
  constexpr std::int64_t kSamples = 1 << 18;
  const std::vector<int> counts = BlockMeanCounts(kSamples);
  int alarms = 0, held_alarms = 0;
  for (int t = 0; t < kTrials; ++t) {
    const std::vector<double> y = independent::Generate(recipe, kSamples, 9700 + t, 0);
    ViewResiduals change, held, trend;
    BlockMeanResiduals(y, 1.0 / recipe.rate_hz, counts, model, ModelK(model), &change, &trend);
    BlockMeanResiduals(y, 1.0 / recipe.rate_hz, counts, model, 0.0, &held, &trend);
    alarms += MaxAbsZ(change) > OwnThreshold(0.05, static_cast<int>(counts.size()));
    held_alarms += MaxAbsZ(held) > OwnThreshold(0.05, static_cast<int>(counts.size()));
  }
  const RateInterval ci = WilsonInterval(static_cast<double>(alarms) / kTrials, kTrials);
  std::printf("profiled change_point: %d / %d false alarms (held K: %d), Wilson 95 %% [%.4f, %.4f]\n", alarms,
              kTrials, held_alarms, ci.low, ci.high);
  EXPECT_LE(ci.high, 0.08) << alarms << " / " << kTrials;
}

// A 20 deg/h step at 2500 s on B 2 deg/h (a 15 deg/h step on B 3 is at the detection limit: see
// AStepAFreeKAbsorbedIsFlaggedWithKProfiled). The
// change-point view flags it and places it within one block (140.6 s); the bias-step candidate
// starts there. Old code: verdict none, no region.
TEST(BlockMeansStat, StepIsFlaggedAndLocated) {
  Sensor sensor;
  sensor.b_deg_per_h = 2.0;
  independent::Recipe r = RecipeOf(sensor);
  r.bias_step = independent::BiasStep{20.0 * kDegPerHour, 2500.0};
  const DiagnosisSummary s = DiagnoseIndependent(r, kIssueSamples, 21);
  const GapRegion* region = RegionOf(s, View::kChangePoint);
  ASSERT_NE(region, nullptr) << Regions(s);
  EXPECT_GT(region->mean_z, 0.0);  // the level rises
  EXPECT_NEAR(region->time_s, 2500.0, 9000.0 / 64) << Regions(s);
  const CandidateResult* step = CandidateOf(s, "bias_step");
  ASSERT_NE(step, nullptr) << testing::DescribeVerdict(s);
  EXPECT_NEAR(step->effects[0].params.at("time_s"), 2500.0, 30.0);
  // The size from the record's means either side (its slow wander biases it).
  EXPECT_NEAR(step->effects[0].params.at("size_rad_per_s") / kDegPerHour, 20.0, 8.0);
}

// A 60 deg/h warm-up drift (tw 600 s) on B 3 deg/h: the trend view flags it with its time constant
// and the verdict names it. Old code: unexplained (the drift candidate closed the gap but its
// OAVAR-only score was negative).
TEST(BlockMeansStat, DriftIsFlaggedAndNamed) {
  independent::Recipe r = RecipeOf(Sensor{});
  r.warmup_drift = independent::WarmupDrift{60.0 * kDegPerHour, 600.0};
  const DiagnosisSummary s = DiagnoseIndependent(r, kIssueSamples, 22);
  const GapRegion* region = RegionOf(s, View::kTrend);
  ASSERT_NE(region, nullptr) << Regions(s);
  EXPECT_GT(region->mean_z, 0.0);  // settles from above
  EXPECT_GT(region->time_s, 600.0 / 1.5);
  EXPECT_LT(region->time_s, 600.0 * 1.5);
  EXPECT_EQ(s.verdict, "exponential_drift") << testing::DescribeVerdict(s);
}

// A 4 deg/h telegraph with 60 s mean dwell on B 3 deg/h: flagged (by the OAVAR view, not the
// block-mean ones: a stationary process has no level change for them) and named as its Allan
// equivalent, the telegraph listed beside it.
TEST(BlockMeansStat, TelegraphIsFlagged) {
  independent::Recipe r = RecipeOf(Sensor{});
  r.telegraph = independent::Telegraph{4.0 * kDegPerHour, 60.0};
  const DiagnosisSummary s = DiagnoseIndependent(r, kIssueSamples, 23);
  EXPECT_TRUE(s.significant);
  EXPECT_TRUE(s.verdict == "random_telegraph" || s.verdict == "gauss_markov") << testing::DescribeVerdict(s);
  EXPECT_EQ(RegionOf(s, View::kChangePoint), nullptr) << Regions(s);
}

}  // namespace
}  // namespace allanlab::experiments
