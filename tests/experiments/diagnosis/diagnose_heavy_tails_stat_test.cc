// `diagnose` on white noise with a heavier law than the Gaussian and no isolated spikes, made by
// the independent generator (Student-t draws of the same variance): the kurtosis view flags it at
// the shortest taus and the outliers candidate, started from the first differences' excess
// kurtosis (a contaminated normal), names it. Fixed seed, 3.6e4-sample record (seconds).
#include <gtest/gtest.h>

#include "experiments/diagnosis/diagnose.h"
#include "independent/generate.h"
#include "independent/recipe.h"
#include "tests/support/diagnosis_record.h"

namespace allanlab::experiments {
namespace {

// Student-t with 12 degrees of freedom: excess kurtosis 0.75 in the draws, 0.375 in the first
// differences (the sum of two), 14 standard errors of a Gaussian's (sqrt(24 / n) = 0.026); fewer
// than 3 draws beyond 7 sigma of the MAD, so the spike count alone does not start the candidate
// (the record was 'unexplained' when it did not).
TEST(DiagnoseHeavyTailsStatTest, StudentTWhiteNoiseIsNamedOutliers) {
  independent::Recipe r;
  r.rate_hz = 100.0;
  r.noise.arw_rad_per_sqrt_s = 1e-4;
  r.noise.white_law = independent::WhiteLaw::kStudentT;
  r.noise.student_t_dof = 12.0;
  r.noise.rrw_rad_per_s_per_sqrt_s = 1e-6;
  const std::vector<double> record = independent::Generate(r, testing::kDiagnosisTestSamples, 71, 0);
  DiagnoseOptions options;
  options.trials = 12;
  DiagnosisSummary s;
  ASSERT_TRUE(DiagnoseRecord(options, record, SampleClock::FromRateHz(r.rate_hz), &s)) << s.message;
  ASSERT_TRUE(s.significant);
  EXPECT_EQ(s.verdict, "outliers") << testing::DescribeVerdict(s);
}

}  // namespace
}  // namespace allanlab::experiments
