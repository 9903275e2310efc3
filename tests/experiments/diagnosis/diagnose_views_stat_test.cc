// The false-alarm rate of the Monte Carlo views of the gap diagnosis (hadamard, halves, dynamic,
// psd, kurtosis: gap.h's Student-t prediction interval from `trials` simulated records of the
// fitted model), which the OAVAR-only control test does not reach. Few trials (8) on purpose:
// there the t quantile differs most from the normal one (a normal-quantile z, or an sd without
// the sqrt(1 + 1/n) of a prediction, would flag several times alpha), so the test can fail.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <vector>

#include "experiments/diagnosis/diagnose.h"
#include "sim/sensor_model.h"
#include "tests/support/diagnosis_control.h"

namespace allanlab::experiments {
namespace {

// 40 control records (white + random walk, 8192 samples at 100 Hz: every view present), each
// with its own envelope seed so that the records' flags are independent. A record counts when a
// Monte Carlo view (not OAVAR) has a point beyond the Bonferroni level over all points of all
// views, whose share alpha * (MC points / all points) is below alpha = 0.05. Under
// Binomial(40, 0.05), P(X >= 7) = 0.0036: the false-fail rate of the bound X <= 6.
TEST(DiagnoseViewsStatTest, MonteCarloViewsFlagControlsAtMostAtTheStatedRate) {
  const sim::SensorModel model = testing::DiagnosisControlModel();
  DiagnoseOptions options;
  options.trials = 8;
  options.false_alarm = 0.05;
  options.max_effects = 1;
  options.effects.clear();  // where, not which: no candidate refits
  int flagged = 0, with_all_views = 0;
  for (int r = 0; r < 40; ++r) {
    const std::vector<double> record = model.Generate(5150, r, 8192);
    options.seed = 1000 + static_cast<std::uint64_t>(r);
    DiagnosisSummary s;
    ASSERT_TRUE(DiagnoseRecord(options, record, SampleClock::FromPeriodS(0.01), &s)) << s.message;
    if (s.before.views.size() == static_cast<std::size_t>(kNumViews)) ++with_all_views;
    bool mc = false;
    for (const GapRegion& g : s.regions) mc |= g.view != View::kOavar;
    if (mc) ++flagged;
  }
  RecordProperty("flagged", flagged);
  std::printf("%d of 40 controls flagged by the Monte Carlo views\n", flagged);
  EXPECT_EQ(with_all_views, 40) << "a Monte Carlo view is missing, so it would not be tested";
  EXPECT_LE(flagged, 6) << flagged << " of 40 controls flagged by the Monte Carlo views at alpha = 0.05";
}

}  // namespace
}  // namespace allanlab::experiments
