// Monte Carlo check of the exact MVAR and OHVAR moments (exact_edf.h ModelStatisticMoments) on
// records of the real generators, white + discrete random walk (both exact: no flicker start-up
// transient). The mean of `kTrials` estimates must lie within z SD / sqrt(trials) of E; the
// sample variance within z times its standard error, sd(s^2)/s^2 = sqrt((2 + 12/edf) / trials)
// (a chi-square-like estimate with `edf` degrees of freedom has excess kurtosis 12/edf). z = 5.
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "estimators/avar.h"
#include "estimators/exact_edf.h"
#include "tests/support/monte_carlo.h"

namespace allanlab::estimators {
namespace {

TEST(ExactQuadraticMomentsStat, ModifiedAndHadamardMomentsMatchMonteCarlo) {
  constexpr int kTrials = 2000;
  constexpr std::int64_t kN = 1024;
  constexpr double kZ = testing_support::kZ;
  sim::SensorModel model;
  model.sample_clock = SampleClock::FromRateHz(10.0);
  model.terms.push_back(sim::WhiteRateNoise{1e-3});
  model.terms.push_back(sim::RandomWalkRate{1e-4});
  const std::vector<std::int64_t> ms = {1, 4, 16, 64, 256};
  for (Statistic s : {Statistic::kModifiedAllan, Statistic::kHadamardOverlapping}) {
    const std::vector<AvarMoments> exact = ModelStatisticMoments(model, s, ms, kN);
    std::vector<double> sum(ms.size(), 0.0), sum_sq(ms.size(), 0.0);
    AvarOptions options;
    options.statistic = s;
    options.sample_clock = SampleClock::FromPeriodS(0.1);
    options.taus.kind = TauGridKind::kExplicit;
    for (std::int64_t m : ms) options.taus.explicit_taus_s.push_back(0.1 * static_cast<double>(m));
    options.confidence_method = ConfidenceMethod::kNone;
    for (int trial = 0; trial < kTrials; ++trial) {
      const std::vector<double> y = model.Generate(77, static_cast<std::uint64_t>(trial), kN);
      AvarSummary summary;
      ASSERT_TRUE(ComputeAvar(options, y, &summary)) << summary.message;
      ASSERT_EQ(summary.points.size(), ms.size());
      for (std::size_t i = 0; i < ms.size(); ++i) {
        const double v = summary.points[i].value / exact[i].mean;  // scale-free
        sum[i] += v;
        sum_sq[i] += v * v;
      }
    }
    for (std::size_t i = 0; i < ms.size(); ++i) {
      const double mean = sum[i] / kTrials;
      const double variance = (sum_sq[i] - kTrials * mean * mean) / (kTrials - 1);
      const double rel_var = exact[i].variance / (exact[i].mean * exact[i].mean);
      const double edf = exact[i].edf();
      const std::string where = std::string(StatisticId(s)) + " m=" + std::to_string(ms[i]) +
                                " edf=" + std::to_string(edf);
      EXPECT_NEAR(mean, 1.0, kZ * std::sqrt(rel_var / kTrials)) << where;
      EXPECT_NEAR(variance / rel_var, 1.0, kZ * std::sqrt((2.0 + 12.0 / edf) / kTrials)) << where;
    }
  }
}

}  // namespace
}  // namespace allanlab::estimators
