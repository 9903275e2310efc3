// Two records of the independent benchmark (seed 4; 32 and 42 min at 100 Hz from independent/, its
// own discretization and random numbers) whose right effect closed the gap but lost the verdict,
// redrawn here from the benchmark's own draw and diagnosed with `--model N,B,K`:
//   #67, a -35 deg/h bias step at 1006 s: named a Gauss-Markov of correlation time 5902 s in a
//     1931 s record (score 56 against the step's 37; held-out chi2 155 against 48). A correlation
//     time beyond half the record is not determined (physical_bounds.h);
//   #160, an angle quantizer whose samples take 14 values: named a band-limit, whose score was
//     12 above the quantizer's over 135 points (held-out shrink 3.3x against 6.9x). Scores that
//     close are a tie the held-out shrink decides (verdict.cc, ScoreTie).
// Both fail on the code before those two rules.
// And one of seed 5, whose right effect did not close the gap:
//   #150, a 2nd-order impulse-invariant 75 Hz low-pass at 800 Hz, every 8th sample kept: the
//     aliasing makes the 100 Hz output blue near Nyquist. The band-limit's start was fitted with a
//     free Q, which took that rise, so a CIC filter won the start and its refit without Q left
//     OAVAR |z| 11; the record was unexplained. Starts are now fitted with the refit's terms
//     (candidate_estimate.h, EstimateInputs::fitted_terms).
//   #355, a 145 deg/h random telegraph of 35 s mean dwell: its Allan bump fitted as 109 deg/h and
//     24 s beside a large K, whose model the kurtosis view rejected (|z| 8.6); unexplained. A
//     telegraph whose two levels the record shows is now read off the record and held there
//     (effect.h, HeldAtItsStart).
//   #235, an angle quantizer whose 242093 samples take 16 values: named a band-limit that scored 19
//     above the quantizer over 130 points (beyond the tie; both closed the gap). A quantizer whose
//     step is the record's value grid now names it (verdict.cc, ResolveValueGrid).
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "experiments/diagnosis/diagnose.h"
#include "tests/support/diagnosis_record.h"

namespace allanlab::experiments {
namespace {

// Record `index` of the committed draw with `seed`, which must have the benchmark's `samples` and
// truth `effect`, diagnosed with `--model N,B,K` and `trials` Monte Carlo records: its verdict.
void ExpectVerdict(std::uint64_t seed, int index, std::int64_t samples, const char* effect, int trials,
                   const char* verdict) {
  IndependentCase c;
  const std::vector<double> record = testing::IndependentBenchmarkRecord(testing::CommittedBenchmarkDraw(), seed, index, &c);
  ASSERT_EQ(c.num_samples, samples) << "#" << index;
  ASSERT_EQ(c.effect_id, effect) << "#" << index;
  DiagnoseOptions options = testing::UserModelNBK();
  options.trials = trials;
  DiagnosisSummary s;
  ASSERT_TRUE(DiagnoseRecord(options, record, SampleClock::FromRateHz(c.recipe.rate_hz), &s)) << s.message;
  EXPECT_EQ(s.verdict, verdict) << "#" << index << ": " << testing::DescribeVerdict(s);
}

// The benchmark's 30 Monte Carlo trials (with the tests' 12 the quantizer's Monte Carlo views left
// it at max |z| 4.0, past the threshold).
TEST(DiagnoseBenchmarkChoicesStatTest, AStepAndAnAngleQuantizerWinTheirVerdicts) {
  ExpectVerdict(4, 67, 193120, "bias_step", 30, "bias_step");
  ExpectVerdict(4, 160, 250304, "angle_quantization", 30, "angle_quantization");
}

TEST(DiagnoseBenchmarkChoicesStatTest, APointSampledFilterAboveNyquistIsABandLimit) {
  ExpectVerdict(5, 150, 234006, "bandwidth", testing::UserModelNBK().trials, "bandwidth");
}

TEST(DiagnoseBenchmarkChoicesStatTest, ATelegraphWhoseLevelsShowIsNamed) {
  ExpectVerdict(5, 355, 278186, "random_telegraph", testing::UserModelNBK().trials, "random_telegraph");
}

TEST(DiagnoseBenchmarkChoicesStatTest, SamplesOnAValueGridNameTheQuantizer) {
  ExpectVerdict(5, 235, 242093, "angle_quantization", testing::UserModelNBK().trials, "angle_quantization");
}

}  // namespace
}  // namespace allanlab::experiments
