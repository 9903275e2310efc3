// Statistical checks that `diagnose` names effects whose signature is not a bump in the Allan
// curve: a band-limit (short taus bent below the white level, no ADEV maximum), a bias
// step (halves and dynamic views). Fixed seeds; records of 3.6e4 samples so
// each test takes seconds.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "experiments/diagnosis/diagnose.h"
#include "sim/sensor_model.h"
#include "tests/support/diagnosis_control.h"
#include "tests/support/diagnosis_record.h"

namespace allanlab::experiments {
namespace {

using testing::DescribeVerdict;
using testing::DiagnoseShortRecord;

// A first-order low-pass at 4 Hz on the control model (100 Hz, point-sampled from L = 8, the
// chain of effect.h): the white level of the taus below ~1/(2 pi fc) = 0.04 s drops by up to 25x,
// far outside the exact OAVAR band (EDF ~ N/m ~ 1e4 there). The candidate fits fc jointly with the
// linear terms; the cutoff is set by the ~4 taus of the bend, each with a relative sd of ~1 %,
// so 20 % is a loose bound.
TEST(DiagnoseEffectsStatTest, BandLimitIsNamedWithItsCutoff) {
  sim::SensorModel model = testing::DiagnosisControlModel();
  model.band_limit.kind = sim::LowPassKind::kFirstOrder;
  model.band_limit.cutoff_hz = 4.0;
  model.band_limit.oversampling = 8;
  model.band_limit.sampling = sim::OutputSampling::kPoint;
  const DiagnosisSummary s = DiagnoseShortRecord(model, 31);
  ASSERT_TRUE(s.significant);
  // A first-order low-pass of the white noise is a Gauss-Markov process of Tc = 1/(2 pi fc) with
  // no white floor left: either reading is right, the other named as also consistent.
  const CandidateResult& c = s.candidates[s.verdict_candidate];
  if (s.verdict == "gauss_markov") {
    bool listed = false;
    for (const auto& a : s.also_consistent) listed |= a.effect == "bandwidth";
    EXPECT_TRUE(listed) << DescribeVerdict(s);
    EXPECT_NEAR(1.0 / (2.0 * M_PI * c.effects[0].params.at("correlation_time_s")), 4.0, 0.8);
    return;
  }
  ASSERT_EQ(s.verdict, "bandwidth") << DescribeVerdict(s);
  EXPECT_EQ(c.effects[0].params.at("order"), 1.0);
  EXPECT_NEAR(c.effects[0].params.at("cutoff_hz"), 4.0, 0.8);
}

// A bias step of 1e-3 rad/s at 40 % of the record: the halves' white levels are equal but their
// Allan variances at long taus differ by the step's s^2 tau / 3T share, and the rate random walk
// of the control moves the mean by only ~2e-5 rad/s over the record. The change point is found
// at sample resolution: the step's time within 1 s (the white noise, 1e-3 rad/s per sample,
// places a 1e-3 step to a few samples), its size within 20 %.
TEST(DiagnoseEffectsStatTest, BiasStepIsNamedAndPlaced) {
  sim::SensorModel model = testing::DiagnosisControlModel();
  sim::BiasStep step;
  step.size_rad_per_s = 1e-3;
  step.time_s = 0.4 * testing::kDiagnosisTestSamples / model.sample_clock.rate_hz();
  model.terms.push_back(step);
  const DiagnosisSummary s = DiagnoseShortRecord(model, 32);
  ASSERT_TRUE(s.significant);
  ASSERT_EQ(s.verdict, "bias_step") << DescribeVerdict(s);
  const auto& p = s.candidates[s.verdict_candidate].effects[0].params;
  EXPECT_NEAR(p.at("time_s"), step.time_s, 1.0);
  EXPECT_NEAR(p.at("size_rad_per_s"), 1e-3, 2e-4);
}

}  // namespace
}  // namespace allanlab::experiments
