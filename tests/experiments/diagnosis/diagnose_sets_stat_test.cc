// `diagnose` on a record that holds two unmodelled effects, each visible on its own in a view of
// its own, made by the independent generator (independent/: continuous-time terms averaged over
// each sample, its own random numbers, Pareto spikes): no single effect closes the gap, forward
// selection names the set, each member with what it adds to the held-out score, and the same
// record limited to single effects is not explained. Fixed seeds, 3.6e4-sample records (seconds
// each).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "experiments/diagnosis/diagnose.h"
#include "experiments/diagnosis/independent_case.h"
#include "independent/recipe.h"
#include "tests/support/diagnosis_record.h"

namespace allanlab::experiments {
namespace {

using testing::DescribeVerdict;

DiagnosisSummary DiagnoseIndependent(const independent::Recipe& r, std::uint64_t seed, int max_effects = 3) {
  DiagnoseOptions options = testing::TestDiagnoseOptions();
  options.max_effects = max_effects;
  return testing::DiagnoseIndependentRecord(r, testing::kDiagnosisTestSamples, seed, options);
}

independent::Recipe Control() {
  independent::Recipe r;
  r.rate_hz = 100.0;
  r.noise.arw_rad_per_sqrt_s = 1e-4;
  r.noise.rrw_rad_per_s_per_sqrt_s = 1e-6;
  return r;
}

bool Names(const DiagnosisSummary& s, const std::string& id) {
  std::size_t start = 0;
  for (;;) {
    const std::size_t plus = s.verdict.find('+', start);
    if (s.verdict.substr(start, plus == std::string::npos ? std::string::npos : plus - start) == id) return true;
    if (plus == std::string::npos) return false;
    start = plus + 1;
  }
}

// A bias step of 1.5e-3 rad/s at 200 s (the change-point view flags it: |z| 5.4 against the
// baseline, threshold 3.5) and spikes at 0.1 Hz of at least 20 white-noise sigmas (the kurtosis:
// |z| 12): the step leaves the spikes' kurtosis, the outliers leave the step's change point, so
// neither alone closes the gap; together they do. Limited to one effect, the record stays
// unexplained (the test's check that selection is what names it).
independent::Recipe StepAndSpikes() {
  independent::Recipe r = Control();
  r.bias_step = independent::BiasStep{1.5e-3, 200.0};
  r.spikes = independent::Spikes{0.1, 0.02, 8.0, false};
  return r;
}

TEST(DiagnoseSetsStatTest, AStepAndSpikesAreNamedAsASetWithWhatEachAdds) {
  const DiagnosisSummary s = DiagnoseIndependent(StepAndSpikes(), 61);
  ASSERT_TRUE(s.significant);
  ASSERT_GE(s.verdict_candidate, 0) << DescribeVerdict(s);
  EXPECT_TRUE(Names(s, "bias_step")) << DescribeVerdict(s);
  EXPECT_TRUE(Names(s, "outliers")) << DescribeVerdict(s);
  EXPECT_TRUE(s.explains_all) << DescribeVerdict(s);
  const CandidateResult& c = s.candidates[s.verdict_candidate];
  ASSERT_EQ(c.effects.size(), 2u) << DescribeVerdict(s);
  EXPECT_TRUE(c.closes_gap);
  for (const EffectInstance& e : c.effects) {
    if (e.effect == Effect::kBiasStep) {
      EXPECT_NEAR(e.params.at("time_s"), 200.0, 2.0);
    }
  }
  ASSERT_EQ(c.steps.size(), 2u);
  for (const auto& step : c.steps) {
    EXPECT_LT(step.heldout_after.chi2, step.heldout_before.chi2) << EffectId(step.added);
  }
  // The second member must have beaten the first alone by the margin.
  EXPECT_LE(c.steps[1].heldout_after.chi2, 0.8 * c.steps[1].heldout_before.chi2);
}

TEST(DiagnoseSetsStatTest, LimitedToOneEffectTheSameRecordIsNotExplained) {
  const DiagnosisSummary s = DiagnoseIndependent(StepAndSpikes(), 61, 1);
  ASSERT_TRUE(s.significant);
  EXPECT_FALSE(s.explains_all) << DescribeVerdict(s);
  EXPECT_FALSE(Names(s, "bias_step") && Names(s, "outliers")) << DescribeVerdict(s);
}

// Spikes at 0.3 Hz (the kurtosis: |z| 12) and a warm-up drift of 7e-4 rad/s settling in 60 s
// that only the trend view flags (|z| 3.8 against a threshold of 3.6; the halves and the OAVAR
// stay within it). The spikes hold the larger held-out shrink, so the drift joins second and can
// earn its place only by what it shows in the trend view.
TEST(DiagnoseSetsStatTest, ADriftSeenOnlyInTheTrendViewJoinsTheSpikes) {
  independent::Recipe r = StepAndSpikes();
  r.bias_step.reset();
  r.warmup_drift = independent::WarmupDrift{7e-4, 60.0};
  r.spikes->rate_hz = 0.3;
  const DiagnosisSummary s = DiagnoseIndependent(r, 61);
  ASSERT_TRUE(s.significant);
  EXPECT_TRUE(Names(s, "exponential_drift")) << DescribeVerdict(s);
  EXPECT_TRUE(Names(s, "outliers")) << DescribeVerdict(s);
  EXPECT_GT(s.before.View(View::kTrend).max_abs_z, s.threshold);
}

// With one effect only, no second member earns its place: the verdict stays a single effect.
TEST(DiagnoseSetsStatTest, OneEffectStaysSingle) {
  independent::Recipe r = Control();
  r.sinusoid = independent::Sinusoid{4e-4, 0.5, 0.3};
  const DiagnosisSummary s = DiagnoseIndependent(r, 52);
  ASSERT_TRUE(s.significant);
  EXPECT_EQ(s.verdict, "harmonic") << DescribeVerdict(s);
}

// A record of the independent benchmark (seed 3, recording 17 of a draw of 600-900 s records at
// 100 Hz, a fifth of them controls): an angle quantizer alone (LSB 9.6e-6 rad) over N, B, K.
// Against the baseline the trend view stays within the threshold (|z| 3.37 < 3.52); the
// quantizer's refit moves it over (3.65), and a warm-up drift of -1.3e-4 rad/s settling in 26 s
// "explained" that and joined the set (angle_quantization+exponential_drift). A member must
// explain part of the record's own gap: the verdict is the quantizer alone.
TEST(DiagnoseSetsStatTest, NoMemberForADepartureAnotherMembersRefitMade) {
  IndependentDrawOptions draw;
  draw.rate_hz = 100.0;
  draw.min_duration_s = 600.0;
  draw.max_duration_s = 900.0;
  draw.control_fraction = 0.2;
  draw.with_resonance = true;
  IndependentCase c;
  const std::vector<double> record = testing::IndependentBenchmarkRecord(draw, 3, 17, &c);
  ASSERT_EQ(c.effect_id, "angle_quantization");
  DiagnoseOptions options;
  options.baseline = DiagnoseOptions::Baseline::kTerms;
  options.terms = {estimators::Coefficient::kN, estimators::Coefficient::kB, estimators::Coefficient::kK};
  DiagnosisSummary s;
  ASSERT_TRUE(DiagnoseRecord(options, record, SampleClock::FromRateHz(c.recipe.rate_hz), &s)) << s.message;
  ASSERT_TRUE(s.significant);
  EXPECT_LE(s.before.View(View::kTrend).max_abs_z, s.threshold);
  EXPECT_FALSE(Names(s, "exponential_drift")) << DescribeVerdict(s);
  EXPECT_EQ(s.verdict, "angle_quantization") << DescribeVerdict(s);
}

}  // namespace
}  // namespace allanlab::experiments
