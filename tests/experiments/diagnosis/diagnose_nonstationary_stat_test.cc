// `diagnose` on records of the length and kind a user brings (2.5 h at 100 Hz, a MEMS gyro with
// white rate noise N 0.15 deg/sqrt(h), bias instability B 3 deg/h and rate random walk
// K 3 deg/h/sqrt(h)), made by the independent generator (independent/: continuous-time terms
// averaged over each sample, its own random numbers), diagnosed against the user's model of the
// IEEE terms N, B, K (`--model N,B,K`). A bias step, a warm-up drift and a random telegraph
// signal are each flagged and named, the step placed in time and its jump not absorbed by a free
// rate random walk; a control stays clean. Fixed seeds, 9e5-sample records.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "experiments/diagnosis/diagnose.h"
#include "independent/generate.h"
#include "independent/recipe.h"
#include "tests/support/diagnosis_record.h"

namespace allanlab::experiments {
namespace {

using estimators::Coefficient;
using testing::DescribeVerdict;

constexpr double kDegPerHour = std::numbers::pi / 180.0 / 3600.0;  // rad/s
constexpr std::int64_t kSamples = 900000;  // 2.5 h

independent::Recipe Gyro() {
  independent::Recipe r = testing::IndependentMemsGyro(0.15, 3.0, 3.0);
  r.noise.bias_rad_per_s = 20.0 * kDegPerHour;
  return r;
}

DiagnosisSummary Diagnose(const independent::Recipe& r, std::uint64_t seed, std::int64_t samples = kSamples) {
  const std::vector<double> record = independent::Generate(r, samples, seed, 0);
  DiagnoseOptions options;
  options.baseline = DiagnoseOptions::Baseline::kTerms;
  options.terms = {Coefficient::kN, Coefficient::kB, Coefficient::kK};
  DiagnosisSummary s;
  EXPECT_TRUE(DiagnoseRecord(options, record, SampleClock::FromRateHz(r.rate_hz), &s)) << s.message;
  return s;
}

double DegPerHourPerSqrtHour(double k_rad_per_s_per_sqrt_s) { return k_rad_per_s_per_sqrt_s / kDegPerHour * 60.0; }

// A 15 deg/h step at 2500 s. The baseline's free K comes out 11 deg/h/sqrt(h) (true 3): held at
// that, the change-point view reads |z| 3.07, below the record's threshold 3.58, and the verdict
// was none. With K profiled (profiled_step.h) |z| 4.05: flagged, named, placed within one 64-block
// length (141 s), and the step candidate's refit leaves K within 3 sigma of a random walk no larger
// than the true one's (the jump is the step's, not K's). This record is the first of the 20 seeds
// in BlockMeansStat.AStepAFreeKAbsorbedIsFlaggedWithKProfiled (15 of them flagged, 10 with K held):
// at 15 deg/h the step sits at the detection limit.
TEST(DiagnoseNonstationaryStatTest, BiasStep) {
  independent::Recipe r = Gyro();
  r.bias_step = independent::BiasStep{15.0 * kDegPerHour, 2500.0};
  const DiagnosisSummary s = Diagnose(r, 5000);
  ASSERT_EQ(s.verdict, "bias_step") << DescribeVerdict(s);
  bool located = false;
  for (const GapRegion& g : s.regions) {
    if (g.view == View::kChangePoint) located = std::abs(g.time_s - 2500.0) < 9000.0 / 64;
  }
  EXPECT_TRUE(located);
  const CandidateResult& c = s.candidates[s.verdict_candidate];
  EXPECT_NEAR(c.effects[0].params.at("time_s"), 2500.0, 9000.0 / 64);
  EXPECT_NEAR(c.effects[0].params.at("size_rad_per_s") / kDegPerHour, 15.0, 8.0);
  const auto& k = c.fit.at(Coefficient::kK);
  const auto& k_baseline = s.baseline.at(Coefficient::kK);
  EXPECT_LT(DegPerHourPerSqrtHour(k.fitted ? k.value_si - 3.0 * k.sigma_si : 0.0), 3.0);
  EXPECT_LT(k.fitted ? k.value_si : 0.0, k_baseline.value_si);
}

// A large step (190 deg/h at 1750 s of a 1 h record) on a sensor with a plain rate random walk (K 8
// deg/h/sqrt(h)). Fitted through the step's expected AVAR, the refit read K from the step's cross
// term with the noise, which swamps K's long-tau AVAR: K left out with an upper limit of ~9x the
// truth (independent benchmark #103: 72.9 deg/h/sqrt(h); the trend view then judged the record's
// random-walk wander at K = 0, |z| 9, and the record stayed unexplained). The terms are now fitted
// to the record less the step: K is measured as well as the record allows without the step,
// fitted with the truth inside 3 sigma or bounded by an upper limit that holds it and is
// informative (< 3x the truth).
TEST(DiagnoseNonstationaryStatTest, LargeBiasStepLeavesTheRandomWalkMeasurable) {
  independent::Recipe r = Gyro();
  r.noise.arw_rad_per_sqrt_s = units::DegPerSqrtHour(0.26);
  r.noise.rrw_rad_per_s_per_sqrt_s = units::DegPerHourPerSqrtHour(8.0);
  r.bias_step = independent::BiasStep{-190.0 * kDegPerHour, 1750.0};
  for (std::uint64_t seed : {5103, 5105}) {
    const DiagnosisSummary s = Diagnose(r, seed, 360000);
    ASSERT_EQ(s.verdict, "bias_step") << "seed " << seed << ": " << DescribeVerdict(s);
    const auto& k = s.candidates[s.verdict_candidate].fit.at(Coefficient::kK);
    if (k.fitted) {
      EXPECT_NEAR(DegPerHourPerSqrtHour(k.value_si), 8.0, 3.0 * DegPerHourPerSqrtHour(k.sigma_si)) << "seed " << seed;
    } else {
      ASSERT_TRUE(k.has_upper_limit) << "seed " << seed;
      EXPECT_GE(DegPerHourPerSqrtHour(k.upper_limit_si), 8.0) << "seed " << seed;
      EXPECT_LT(DegPerHourPerSqrtHour(k.upper_limit_si), 24.0) << "seed " << seed;
    }
  }
}

TEST(DiagnoseNonstationaryStatTest, WarmupDrift) {
  independent::Recipe r = Gyro();
  r.warmup_drift = independent::WarmupDrift{60.0 * kDegPerHour, 600.0};
  const DiagnosisSummary s = Diagnose(r, 102);
  EXPECT_EQ(s.verdict, "exponential_drift") << DescribeVerdict(s);
}

TEST(DiagnoseNonstationaryStatTest, Telegraph) {
  independent::Recipe r = Gyro();
  r.telegraph = independent::Telegraph{4.0 * kDegPerHour, 60.0};
  const DiagnosisSummary s = Diagnose(r, 103);
  EXPECT_EQ(s.verdict, "random_telegraph") << DescribeVerdict(s);
}

TEST(DiagnoseNonstationaryStatTest, Control) {
  const DiagnosisSummary s = Diagnose(Gyro(), 104);
  EXPECT_EQ(s.verdict, "none") << DescribeVerdict(s);
}

}  // namespace
}  // namespace allanlab::experiments
