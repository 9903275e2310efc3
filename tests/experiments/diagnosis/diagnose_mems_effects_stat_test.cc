// `diagnose` on the effects real MEMS gyros show beyond the IEEE 952 terms: a narrowband
// resonance (the ADIS16405 Z axis's line near 20 Hz) and the short correlation of an internal
// moving-average decimator (its X and Y axes), each named with its parameters; and candidates
// whose fit lands outside physics are refused. Fixed seeds, 3.6e4-sample records (seconds each).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "experiments/diagnosis/diagnose.h"
#include "experiments/diagnosis/physical_bounds.h"
#include "independent/recipe.h"
#include "sim/sensor_model.h"
#include "tests/support/diagnosis_control.h"
#include "tests/support/diagnosis_record.h"

namespace allanlab::experiments {
namespace {

using testing::DescribeVerdict;
using testing::DiagnoseShortRecord;

// A resonance at 20 Hz (damping 0.04, line width 1.6 Hz) with the white noise's own variance:
// the OAVAR at m = 2..4 (tau about half a period) departs by tens of percent, where the band is a
// few percent wide. The Welch start finds the line to a bin (0.1 Hz); the fit then holds f0 to
// well within 1 Hz and the damping within a factor 2 (the width is set by a handful of taus).
TEST(DiagnoseMemsEffectsStatTest, ResonanceIsNamedWithFrequencyAndDamping) {
  sim::SensorModel model = testing::DiagnosisControlModel();
  model.terms.push_back(sim::Resonance{1e-3, 20.0, 0.04});
  const DiagnosisSummary s = DiagnoseShortRecord(model, 41);
  ASSERT_TRUE(s.significant);
  ASSERT_EQ(s.verdict, "resonance") << DescribeVerdict(s);
  const auto& p = s.candidates[s.verdict_candidate].effects[0].params;
  EXPECT_NEAR(p.at("frequency_hz"), 20.0, 1.0) << DescribeVerdict(s);
  EXPECT_GT(p.at("damping"), 0.02) << DescribeVerdict(s);
  EXPECT_LT(p.at("damping"), 0.08) << DescribeVerdict(s);
}

// A moving average 2.5 output periods long (internal rate 8 fs): adjacent outputs share 60 % of
// their window, the next 20 %, none beyond, a shape no first- or second-order low-pass has. The
// band-limit candidate fits every family and names the box.
TEST(DiagnoseMemsEffectsStatTest, MovingAverageDecimatorIsNamedByItsFamily) {
  sim::SensorModel model = testing::DiagnosisControlModel();
  model.band_limit = {sim::LowPassKind::kMovingAverage, 0.44294647 * 100.0 / 2.5, 8, sim::OutputSampling::kPoint};
  const DiagnosisSummary s = DiagnoseShortRecord(model, 42);
  ASSERT_TRUE(s.significant);
  ASSERT_EQ(s.verdict, "bandwidth") << DescribeVerdict(s);
  const EffectInstance& e = s.candidates[s.verdict_candidate].effects[0];
  EXPECT_EQ(EffectLabel(e), "bandwidth (moving_average)") << DescribeVerdict(s);
  EXPECT_NEAR(e.params.at("cutoff_hz"), 0.44294647 * 100.0 / 2.5, 2.0) << DescribeVerdict(s);
}

// A second-order Butterworth by the bilinear transform at the output rate (independent/: its own
// discretization), its cutoff at the highest such a filter takes, 0.45 fs = 45 Hz at 100 Hz: it
// still bends the shortest taus. Screened only up to 38 Hz and refused within 2 % of 45 Hz, it
// was fitted as an analog filter and left unexplained (sim/'s benchmark draws these). Named
// `bandwidth` of the digital second-order family, its cutoff within 2 Hz.
TEST(DiagnoseMemsEffectsStatTest, ADigitalFilterAtItsHighestCutoffIsNamed) {
  independent::Recipe r = testing::IndependentMemsGyro(0.3, 3.0, 3.0);
  r.low_pass = {independent::LowPassDesign::kSecondOrderBilinear, 45.0, 1, independent::Decimation::kPoint};
  const DiagnosisSummary s = testing::DiagnoseIndependentRecord(r, 360000, 9101, testing::UserModelNBK());
  ASSERT_TRUE(s.significant);
  ASSERT_EQ(s.verdict, "bandwidth") << DescribeVerdict(s);
  const EffectInstance& e = s.candidates[s.verdict_candidate].effects[0];
  EXPECT_EQ(EffectLabel(e), "bandwidth (digital2_bilinear)") << DescribeVerdict(s);
  EXPECT_NEAR(e.params.at("cutoff_hz"), 45.0, 2.0) << DescribeVerdict(s);
}

TEST(PhysicalBoundsTest, EachImpossibleFitIsRefusedWithItsReason) {
  const SampleClock clock = SampleClock::FromRateHz(100.0);
  const double length = 3600.0;
  struct Case {
    EffectInstance e;
    const char* reason;
  };
  const Case cases[] = {
      // The first-order family's chain runs at 8 x 100 Hz: its highest cutoff is 0.45 x 800 Hz.
      {{Effect::kBandwidth, {{"cutoff_hz", 359.0}, {"order", 1.0}}}, "the fit ran to its edge"},
      {{Effect::kGaussMarkov, {{"sigma_rad_per_s", 1e-3}, {"correlation_time_s", 0.004}}}, "below the sample period"},
      {{Effect::kRandomTelegraph, {{"amplitude_rad_per_s", 1e-3}, {"mean_dwell_s", 0.015}}}, "below the sample period"},
      // Correlation times beyond half the record: a random walk of the rate over it.
      {{Effect::kGaussMarkov, {{"sigma_rad_per_s", 1e-3}, {"correlation_time_s", 1801.0}}}, "longer than half the record"},
      {{Effect::kRandomTelegraph, {{"amplitude_rad_per_s", 1e-3}, {"mean_dwell_s", 3602.0}}}, "longer than half the record"},
      {{Effect::kHarmonic, {{"amplitude_rad_per_s", 1e-3}, {"frequency_hz", 50.0}}}, "not below the Nyquist"},
      {{Effect::kResonance, {{"sigma_rad_per_s", 1e-3}, {"frequency_hz", 70.0}, {"damping", 0.05}}}, "not below the Nyquist"},
      {{Effect::kResonance, {{"sigma_rad_per_s", 1e-3}, {"frequency_hz", 40.0}, {"damping", 0.9}}}, "not a line"},
      // Damping above 1/sqrt(2): no peak in the spectrum (a Gauss-Markov's bump).
      {{Effect::kResonance, {{"sigma_rad_per_s", 1e-3}, {"frequency_hz", 0.23}, {"damping", 0.95}}}, "no peak"},
      {{Effect::kResonance, {{"sigma_rad_per_s", 1e-3}, {"frequency_hz", 2.0}, {"damping", 0.71}}}, "no peak"},
      // Line width 2 zeta f0 = 1.5e-4 Hz against the record's resolution 1 / 3600 s.
      {{Effect::kResonance, {{"sigma_rad_per_s", 1e-3}, {"frequency_hz", 0.05}, {"damping", 0.0015}}}, "the harmonic"},
      // At the fit's floor: a sinusoid.
      {{Effect::kResonance, {{"sigma_rad_per_s", 1e-3}, {"frequency_hz", 2.0}, {"damping", 0.001}}}, "at the fit's floor"},
      {{Effect::kExponentialDrift, {{"amplitude_rad_per_s", 1e-3}, {"time_constant_s", 1e-3}}}, "below the sample period"},
      {{Effect::kBiasStep, {{"size_rad_per_s", 1e-3}, {"time_s", 4000.0}}}, "outside the record"},
  };
  for (const Case& c : cases) {
    std::string why;
    EXPECT_FALSE(PhysicallyPossible(c.e, clock, length, &why)) << EffectId(c.e.effect);
    EXPECT_NE(why.find(c.reason), std::string::npos) << why;
    EXPECT_NE(why.find("physically impossible"), std::string::npos) << why;
  }
  const EffectInstance fine[] = {
      {Effect::kBandwidth, {{"cutoff_hz", 30.0}, {"order", 2.0}}},
      {Effect::kGaussMarkov, {{"sigma_rad_per_s", 1e-3}, {"correlation_time_s", 0.05}}},
      {Effect::kGaussMarkov, {{"sigma_rad_per_s", 1e-3}, {"correlation_time_s", 1800.0}}},
      {Effect::kRandomTelegraph, {{"amplitude_rad_per_s", 1e-3}, {"mean_dwell_s", 3600.0}}},
      {Effect::kResonance, {{"sigma_rad_per_s", 1e-3}, {"frequency_hz", 20.0}, {"damping", 0.04}}},
      {Effect::kResonance, {{"sigma_rad_per_s", 1e-3}, {"frequency_hz", 2.0}, {"damping", 0.7}}},  // a broad peak
      {Effect::kResonance, {{"sigma_rad_per_s", 1e-3}, {"frequency_hz", 0.5}, {"damping", 0.002}}},  // 2e-3 Hz wide
      // Above the output's Nyquist frequency, below the 800 Hz chain's: a real sensor's filter.
      {Effect::kBandwidth, {{"cutoff_hz", 85.0}, {"order", 2.0}}},
      // A filter at the output rate at its highest cutoff, 0.45 fs: a real digital filter's.
      {Effect::kBandwidth, {{"cutoff_hz", 45.0}, {"order", 2.0}, {"family", 7.0}}},
      {Effect::kBiasStep, {{"size_rad_per_s", 1e-3}, {"time_s", 100.0}}},
  };
  for (const EffectInstance& e : fine) {
    std::string why;
    EXPECT_TRUE(PhysicallyPossible(e, clock, length, &why)) << why;
  }
}

// White noise through a first-order low-pass at 40 Hz (correlation time 4 ms, below the 10 ms
// sample period) and a step: a Gauss-Markov candidate could only mimic the filter with an
// impossible correlation time; whatever the candidates, none reported carries one.
TEST(DiagnoseMemsEffectsStatTest, NoReportedCandidateBreaksAPhysicalBound) {
  sim::SensorModel model = testing::DiagnosisControlModel();
  model.band_limit = {sim::LowPassKind::kFirstOrder, 40.0, 8, sim::OutputSampling::kPoint};
  const DiagnosisSummary s = DiagnoseShortRecord(model, 43);
  for (const CandidateResult& c : s.candidates) {
    std::string why;
    EXPECT_TRUE(PhysicallyPossible(c.effects, model.sample_clock, testing::kDiagnosisTestSamples / model.sample_clock.rate_hz(), &why))
        << why << " " << DescribeVerdict(s);
  }
}

}  // namespace
}  // namespace allanlab::experiments
