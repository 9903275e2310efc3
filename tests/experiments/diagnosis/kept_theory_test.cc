// A diagnosis keeps each model's exact OAVAR (DiagnosisSummary::baseline_theory,
// CandidateResult::theory and heldout_theory) for the views, the held-out score and the plot that
// read it again. What it keeps must be what ExactOavar gives for that model and curve, bit for
// bit: otherwise the plot's band and the views would describe another model than the verdict's.
#include <gtest/gtest.h>

#include <vector>

#include "experiments/diagnosis/diagnose.h"
#include "experiments/diagnosis/envelope.h"
#include "sim/bias_step.h"
#include "tests/support/diagnosis_control.h"

namespace allanlab::experiments {
namespace {

void ExpectSameBits(const OavarTheory& kept, const OavarTheory& fresh) {
  ASSERT_FALSE(kept.mean.empty());
  EXPECT_EQ(kept.mean, fresh.mean);
  EXPECT_EQ(kept.edf, fresh.edf);
}

TEST(KeptTheory, EveryKeptExactOavarIsTheModelsOwn) {
  // A control record with a step in its second half (as DiagnoseHeldoutTest): candidates with a
  // held-out model on either half.
  sim::SensorModel model = testing::DiagnosisControlModel();
  sim::BiasStep step;
  step.size_rad_per_s = 1e-3;
  step.time_s = 400.0;
  model.terms.push_back(step);
  const std::vector<double> record = model.Generate(31, 0, 60000);
  const SampleClock clock = SampleClock::FromPeriodS(0.01);
  DiagnoseOptions options;
  options.trials = 12;
  options.max_effects = 1;
  DiagnosisSummary s;
  ASSERT_TRUE(DiagnoseRecord(options, record, clock, &s)) << s.message;
  ASSERT_FALSE(s.candidates.empty());
  ExpectSameBits(s.baseline_theory, ExactOavar(s.baseline_model, s.curve.m, s.num_samples));
  const std::size_t half = record.size() / 2;
  for (const CandidateResult& c : s.candidates) {
    SCOPED_TRACE(c.id());
    ExpectSameBits(c.theory, ExactOavar(c.model, s.curve.m, s.num_samples));
    if (!c.after.has_heldout) continue;
    estimators::AvarCurve scored;
    std::string why;
    const std::span<const double> rate(record);
    ASSERT_TRUE(RecordCurve(rate.subspan(c.heldout_half * half, half), clock, &scored, &why)) << why;
    ExpectSameBits(c.heldout_theory, ExactOavar(c.heldout_model, scored.m, scored.num_samples));
  }
}

}  // namespace
}  // namespace allanlab::experiments
