// TOTVAR's default-interval EDF (BoundTotalVarianceEdf, as `avar --ci auto` applies it) at the shortest taus. At m = 1 TOTVAR has no
// reflected centres and is the overlapping AVAR itself, so its EDF must be OAVAR's; SP 1065's
// b T/tau gives 1.9 times that for white FM. Coverage on white records made apart from sim/
// (experiments/plain_noise.h, expectation 1/m): 800 trials of 512 samples, binomial standard error
// 1.6 points at 68.3 % and 0.77 at 95 %; tolerance 3.3 standard errors (false-fail rate 0.1 % per
// check). The SP 1065 EDF covered 0.48 [0.43, 0.54] and 0.82 there (300 trials): 12 and 17
// standard errors off, so the checks fail on it.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "estimators/avar.h"
#include "estimators/confidence.h"
#include "experiments/plain_noise.h"

namespace allanlab::estimators {
namespace {

TEST(TotalVarianceAutoEdf, IsOverlappingAvarsAtMOneAndSp1065AtLongTaus) {
  for (std::int64_t n : {512, 4096}) {
    for (int alpha : {0, -1, -2}) {
      const double oavar = StatisticEdf(Statistic::kAllanOverlapping, alpha, 1, n, 1.0);
      EXPECT_DOUBLE_EQ(BoundTotalVarianceEdf(StatisticEdf(Statistic::kTotal, alpha, 1, n, 1.0), oavar, 1, n), oavar);
    }
    // At m = N/8 the bound does not bind for flicker and random walk: SP 1065 stands.
    for (int alpha : {-1, -2}) {
      const double total = StatisticEdf(Statistic::kTotal, alpha, n / 8, n, 1.0);
      EXPECT_DOUBLE_EQ(BoundTotalVarianceEdf(total, StatisticEdf(Statistic::kAllanOverlapping, alpha, n / 8, n, 1.0), n / 8, n),
                       total);
    }
  }
  // `--ci gr` keeps Stable32's SP 1065 EDF.
  EXPECT_GT(StatisticEdf(Statistic::kTotal, 0, 1, 512, 1.0),
            1.8 * StatisticEdf(Statistic::kAllanOverlapping, 0, 1, 512, 1.0));
}

TEST(TotalVarianceAutoEdf, DefaultIntervalsCoverAtTheShortestTaus) {
  constexpr int kTrials = 800;
  constexpr std::int64_t kSamples = 512;
  for (std::int64_t m : {1, 2}) {
    const double expected = experiments::PlainExpectedAvar(experiments::PlainNoise::kWhite, m);
    int in68 = 0, in95 = 0;
    for (int trial = 0; trial < kTrials; ++trial) {
      const std::vector<double> record =
          experiments::GeneratePlain(experiments::PlainNoise::kWhite, kSamples, 20261124, trial);
      AvarOptions options;
      options.statistic = Statistic::kTotal;
      options.confidence_method = ConfidenceMethod::kAuto;
      options.taus.kind = TauGridKind::kExplicit;
      options.taus.explicit_taus_s = {static_cast<double>(m)};
      AvarSummary summary;
      ASSERT_TRUE(ComputeAvar(options, record, &summary)) << summary.message;
      ASSERT_EQ(summary.points.size(), 1u);
      const AvarPoint& p = summary.points[0];
      in68 += ChiSquareInterval(p.value, p.edf, 0.683).low <= expected &&
              expected <= ChiSquareInterval(p.value, p.edf, 0.683).high;
      in95 += ChiSquareInterval(p.value, p.edf, 0.95).low <= expected &&
              expected <= ChiSquareInterval(p.value, p.edf, 0.95).high;
    }
    const double c68 = static_cast<double>(in68) / kTrials, c95 = static_cast<double>(in95) / kTrials;
    EXPECT_NEAR(c68, 0.683, 3.3 * std::sqrt(0.683 * 0.317 / kTrials)) << "m = " << m;
    EXPECT_NEAR(c95, 0.95, 3.3 * std::sqrt(0.95 * 0.05 / kTrials)) << "m = " << m;
  }
}

}  // namespace
}  // namespace allanlab::estimators
