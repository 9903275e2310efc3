// Statistical checks of the gap diagnosis (issue 6): records drawn from the model itself are
// flagged at no more than the stated false-alarm rate, and a record with spikes shows a gap in
// the kurtosis view. Fixed seeds; short records so the whole file takes seconds.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "experiments/diagnosis/diagnose.h"
#include "sim/sensor_model.h"
#include "sim/units.h"

namespace allanlab::experiments {
namespace {

sim::SensorModel Control() {
  sim::SensorModel model;
  model.sample_rate_hz = 100.0;
  sim::WhiteRateNoise white;
  white.arw_rad_per_sqrt_s = 1e-4;
  sim::RandomWalkRate walk;
  walk.rrw_rad_per_s_per_sqrt_s = 1e-6;
  model.terms = {white, walk};
  return model;
}

// 20 controls on the exact OAVAR view (trials = 0 keeps the test to seconds), alpha = 0.05: the count of flagged records is at most Binomial(20, 0.05) (the
// Bonferroni level is conservative), and P(X >= 5) = 0.0026 under it.
TEST(DiagnoseStatTest, ControlsAreCleanAtTheStatedRate) {
  const sim::SensorModel model = Control();
  DiagnoseOptions options;
  options.trials = 0;
  options.false_alarm = 0.05;
  options.try_pairs = false;
  options.envelope_candidates = 1;
  int flagged = 0;
  for (int r = 0; r < 20; ++r) {
    const std::vector<double> record = model.Generate(4242, r, 4096);
    DiagnosisSummary s;
    ASSERT_TRUE(DiagnoseRecord(options, record, 0.01, &s)) << s.message;
    if (s.significant) ++flagged;
    EXPECT_EQ(s.significant, s.verdict != "none");
  }
  EXPECT_LE(flagged, 4) << flagged << " of 20 controls flagged at alpha = 0.05";
}

TEST(DiagnoseStatTest, SpikesShowInTheKurtosisView) {
  sim::SensorModel model = Control();
  sim::Outliers spikes;
  spikes.rate_hz = 0.5;
  spikes.size_rad_per_s = 0.02;  // 20 x the per-sample white noise (1e-4 * sqrt(100) = 1e-3)
  model.terms.push_back(spikes);
  const std::vector<double> record = model.Generate(99, 0, 20000);
  DiagnoseOptions options;
  options.trials = 12;
  DiagnosisSummary s;
  ASSERT_TRUE(DiagnoseRecord(options, record, 0.01, &s)) << s.message;
  EXPECT_TRUE(s.significant);
  // Spikes add white noise to every Allan view; the kurtosis view is where they show.
  bool kurtosis_region = false;
  for (const GapRegion& r : s.regions) kurtosis_region |= r.view == View::kKurtosis;
  EXPECT_TRUE(kurtosis_region);
}

TEST(DiagnoseStatTest, RefusesShortAndNonFiniteRecords) {
  DiagnoseOptions options;
  DiagnosisSummary s;
  std::vector<double> shortrec(100, 1.0);
  EXPECT_FALSE(DiagnoseRecord(options, shortrec, 0.01, &s));
  EXPECT_NE(s.message.find("at least"), std::string::npos) << s.message;
  std::vector<double> constant(5000, 1.0);
  EXPECT_FALSE(DiagnoseRecord(options, constant, 0.01, &s));
  EXPECT_FALSE(s.message.empty());
  std::vector<double> nan = Control().Generate(1, 0, 5000);
  nan[17] = std::nan("");
  EXPECT_FALSE(DiagnoseRecord(options, nan, 0.01, &s));
  EXPECT_NE(s.message.find("sample 17"), std::string::npos) << s.message;
}

}  // namespace
}  // namespace allanlab::experiments
