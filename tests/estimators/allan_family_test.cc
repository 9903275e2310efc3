// The statistic values against the formulas written out directly (tests/support), the drop
// rules, and the input checks of ComputeStatisticValues.
#include "estimators/allan_family.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "tests/support/direct_statistics.h"

namespace allanlab::estimators {
namespace {

using testing_support::DirectStatistic;

constexpr Statistic kAll[] = {
    Statistic::kAllanNonOverlapping,
    Statistic::kAllanOverlapping,
    Statistic::kModifiedAllan,
    Statistic::kHadamardNonOverlapping,
    Statistic::kHadamardOverlapping,
    Statistic::kTotal,
    Statistic::kTime,
};

// White noise plus a random walk plus a bias, so that every statistic sees non-trivial data and
// the mean removal matters.
std::vector<double> TestRecord(std::int64_t n, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  std::normal_distribution<double> normal;
  std::vector<double> y(static_cast<std::size_t>(n));
  double walk = 0.0;
  for (double& v : y) {
    walk += 0.05 * normal(engine);
    v = 3.0 + normal(engine) + walk;
  }
  return y;
}

AvarOptions ExplicitOptions(Statistic s, std::vector<std::int64_t> ms, double tau0 = 1.0) {
  AvarOptions options;
  options.statistic = s;
  options.sample_clock = SampleClock::FromPeriodS(tau0);
  options.taus.kind = TauGridKind::kExplicit;
  for (std::int64_t m : ms) options.taus.explicit_taus_s.push_back(static_cast<double>(m) * tau0);
  return options;
}

// Relative agreement with the direct formulas. Rounding of the prefix sums and of the blocked
// sums costs a few 1e-16 per operation; 1e-11 is far above that and far below any real error.
void ExpectMatchesDirect(Statistic s, std::span<const double> y, std::vector<std::int64_t> ms,
                         double tau0 = 1.0) {
  AvarSummary summary;
  ASSERT_TRUE(ComputeStatisticValues(ExplicitOptions(s, ms, tau0), y, &summary)) << summary.message;
  ASSERT_EQ(summary.points.size(), ms.size()) << StatisticId(s);
  for (const AvarPoint& p : summary.points) {
    const double expected = static_cast<double>(DirectStatistic(s, y, p.m, tau0));
    EXPECT_NEAR(p.value, expected, 1e-11 * expected)
        << StatisticId(s) << " n=" << y.size() << " m=" << p.m;
    EXPECT_EQ(p.terms, TermCount(s, p.m, static_cast<std::int64_t>(y.size())));
    EXPECT_DOUBLE_EQ(p.tau_s, static_cast<double>(p.m) * tau0);
  }
}

TEST(AllanFamily, EveryAveragingFactorOfShortRecordsMatchesDirectFormulas) {
  for (std::int64_t n : {3, 4, 5, 6, 7, 10, 17, 64, 101}) {
    const std::vector<double> y = TestRecord(n, 7 + n);
    for (Statistic s : kAll) {
      std::vector<std::int64_t> ms;
      for (std::int64_t m = 1; m <= MaxAveragingFactor(s, n); ++m) ms.push_back(m);
      ExpectMatchesDirect(s, y, ms, 0.25);
    }
  }
}

// Lengths around the blocking of the fast passes (blocks of 2048 and 4096 starts, 16 lanes).
TEST(AllanFamily, LongRecordsAcrossBlockBoundariesMatchDirectFormulas) {
  for (std::int64_t n : {2047, 2048, 4113, 6150}) {
    const std::vector<double> y = TestRecord(n, n);
    for (Statistic s : kAll) {
      const std::int64_t max_m = MaxAveragingFactor(s, n);
      std::vector<std::int64_t> ms = {1, 2, 3, 4, 7, 8, 16, 17, 32, 64, 100, 128, 255, 256};
      for (std::int64_t m : {max_m / 2, max_m - 1, max_m}) ms.push_back(m);
      std::sort(ms.begin(), ms.end());
      ms.erase(std::unique(ms.begin(), ms.end()), ms.end());
      ExpectMatchesDirect(s, y, ms);
    }
  }
}

// Lags from 32768 on that are octave multiples take the row passes (tiers of 32768 x 128^k),
// other long lags the far block pass; both must agree with the definitions.
TEST(AllanFamily, LongLagsOfEveryPassMatchDirectFormulas) {
  const std::int64_t n = 300000;
  const std::vector<double> y = TestRecord(n, 11);
  ExpectMatchesDirect(Statistic::kAllanOverlapping, y,
                      {1, 2, 3, 4, 8, 16384, 32767, 32768, 40000, 65536, 131072, 149999, 150000});
  ExpectMatchesDirect(Statistic::kHadamardOverlapping, y, {1, 32768, 65536, 70000, 100000});
}

// A warm-up transient of 1000 x the noise in the first 20 % of the record: the reference level
// follows the whole record (phase_integral.h), so the phase stays small and no digits are lost.
TEST(AllanFamily, WarmUpTransientCostsNoDigits) {
  const std::int64_t n = 300000;
  std::vector<double> y = TestRecord(n, 12);
  for (std::int64_t k = 0; k < n / 5; ++k) y[k] += 1000.0;
  ExpectMatchesDirect(Statistic::kAllanOverlapping, y, {1, 2, 16, 1000, 65536});
  ExpectMatchesDirect(Statistic::kAllanNonOverlapping, y, {1, 3, 1000});
  ExpectMatchesDirect(Statistic::kTotal, y, {1, 100, 100000});
}

// A tau's value does not depend on which other taus are computed with it (the octave pass
// pairs m with 2m; the pair and the single kernel must give the same bits).
TEST(AllanFamily, ValueDoesNotDependOnTheRestOfTheGrid) {
  const std::vector<double> y = TestRecord(200000, 3);
  for (Statistic s : kAll) {
    AvarOptions octave;
    octave.statistic = s;
    AvarSummary all;
    ASSERT_TRUE(ComputeStatisticValues(octave, y, &all));
    for (const AvarPoint& p : all.points) {
      AvarSummary one;
      ASSERT_TRUE(ComputeStatisticValues(ExplicitOptions(s, {p.m}), y, &one));
      ASSERT_EQ(one.points.size(), 1u);
      EXPECT_EQ(one.points[0].value, p.value) << StatisticId(s) << " m=" << p.m;
    }
  }
}

// Without a workspace the overlapping statistics rebuild the phase in cache-sized pieces
// instead of storing it (difference_sums.h): the same bits as with one, on lengths around the
// block, checkpoint and tier boundaries, the octave grid (every lag rebuilt) and a decade grid
// (long lags off the tiers: the stored phase again).
TEST(AllanFamily, WithoutAWorkspaceTheSameBits) {
  for (std::int64_t n : {std::int64_t{3}, std::int64_t{101}, std::int64_t{4097},
                         std::int64_t{65543}, std::int64_t{1} << 20, std::int64_t{2200007}}) {
    const std::vector<double> y = TestRecord(n, 11);
    for (Statistic s : {Statistic::kAllanOverlapping, Statistic::kHadamardOverlapping}) {
      for (TauGridKind kind : {TauGridKind::kOctave, TauGridKind::kDecade125}) {
        AvarOptions options;
        options.statistic = s;
        options.taus.kind = kind;
        AvarSummary cold, warm;
        AllanFamilyWorkspace workspace;
        ASSERT_TRUE(ComputeStatisticValues(options, y, &cold)) << cold.message;
        ASSERT_TRUE(ComputeStatisticValues(options, y, &warm, &workspace)) << warm.message;
        ASSERT_EQ(cold.points.size(), warm.points.size());
        for (std::size_t k = 0; k < cold.points.size(); ++k) {
          EXPECT_EQ(cold.points[k].value, warm.points[k].value)
              << StatisticId(s) << " n=" << n << " m=" << cold.points[k].m;
        }
      }
    }
  }
}

TEST(AllanFamily, TimeVarianceIsTauSquaredModifiedOverThree) {
  const std::vector<double> y = TestRecord(500, 1);
  AvarSummary mvar, tvar;
  AvarOptions options;
  options.sample_clock = SampleClock::FromPeriodS(0.01);
  options.statistic = Statistic::kModifiedAllan;
  ASSERT_TRUE(ComputeStatisticValues(options, y, &mvar));
  options.statistic = Statistic::kTime;
  ASSERT_TRUE(ComputeStatisticValues(options, y, &tvar));
  ASSERT_EQ(mvar.points.size(), tvar.points.size());
  for (std::size_t k = 0; k < mvar.points.size(); ++k) {
    const double tau = mvar.points[k].tau_s;
    EXPECT_NEAR(tvar.points[k].value, tau * tau * mvar.points[k].value / 3.0,
                1e-15 * tvar.points[k].value);
  }
}

// Exact values for deterministic signals (docs/theory.md §2: a rate ramp R k tau0 has Allan
// difference R tau, so AVAR = R^2 tau^2 / 2 for every estimator; Hadamard removes it).
TEST(AllanFamily, RateRampGivesExactAllanAndZeroHadamard) {
  const double r = 0.3, tau0 = 0.5;
  std::vector<double> y(1000);
  for (std::size_t k = 0; k < y.size(); ++k) y[k] = r * static_cast<double>(k) * tau0;
  for (Statistic s : {Statistic::kAllanNonOverlapping, Statistic::kAllanOverlapping}) {
    AvarOptions options;
    options.statistic = s;
    options.sample_clock = SampleClock::FromPeriodS(tau0);
    AvarSummary summary;
    ASSERT_TRUE(ComputeStatisticValues(options, y, &summary));
    for (const AvarPoint& p : summary.points) {
      const double expected = r * r * p.tau_s * p.tau_s / 2.0;
      // The phase of a ramp is a parabola ~1e4 times its second difference here, so the
      // differences keep ~12 digits: 1e-10, not 1e-15.
      EXPECT_NEAR(p.value, expected, 1e-10 * expected) << StatisticId(s) << " m=" << p.m;
    }
  }
  for (Statistic s : {Statistic::kHadamardNonOverlapping, Statistic::kHadamardOverlapping}) {
    AvarOptions options;
    options.statistic = s;
    options.sample_clock = SampleClock::FromPeriodS(tau0);
    AvarSummary summary;
    ASSERT_TRUE(ComputeStatisticValues(options, y, &summary));
    for (const AvarPoint& p : summary.points) EXPECT_NEAR(p.value, 0.0, 1e-20) << p.m;
  }
}

TEST(AllanFamily, GeneratedGridsStopAtTheLargestAveragingFactor) {
  const std::vector<double> y = TestRecord(1000, 2);
  for (Statistic s : kAll) {
    AvarOptions options;
    options.statistic = s;
    AvarSummary summary;
    ASSERT_TRUE(ComputeStatisticValues(options, y, &summary)) << summary.message;
    EXPECT_TRUE(summary.dropped.empty());
    // Largest m: 500 (Allan), 333 (n/3 statistics), 999 (total).
    EXPECT_EQ(summary.points.back().m, s == Statistic::kTotal ? 512 : 256);
    EXPECT_EQ(summary.num_samples, 1000);
    EXPECT_TRUE(summary.ok);
  }
}

TEST(AllanFamily, ExplicitTausBeyondTheRecordAreDroppedWithTheReason) {
  const std::vector<double> y = TestRecord(100, 2);
  AvarOptions options = ExplicitOptions(Statistic::kAllanOverlapping, {1, 50, 51, 1000});
  options.taus.explicit_taus_s.push_back(0.2);  // rounds to m = 0
  options.taus.explicit_taus_s.push_back(1.2);  // rounds to m = 1: merged
  AvarSummary summary;
  ASSERT_TRUE(ComputeStatisticValues(options, y, &summary)) << summary.message;
  ASSERT_EQ(summary.points.size(), 2u);
  EXPECT_EQ(summary.points[0].m, 1);
  EXPECT_EQ(summary.points[1].m, 50);
  EXPECT_EQ(summary.points[1].terms, 1);
  ASSERT_EQ(summary.dropped.size(), 3u);
  EXPECT_EQ(summary.dropped[0].m, 0);
  EXPECT_NE(summary.dropped[0].reason.find("m = 0"), std::string::npos)
      << summary.dropped[0].reason;
  EXPECT_EQ(summary.dropped[1].m, 51);
  EXPECT_NE(summary.dropped[1].reason.find("largest averaging factor 50"), std::string::npos)
      << summary.dropped[1].reason;
  EXPECT_EQ(summary.dropped[2].m, 1000);
  EXPECT_DOUBLE_EQ(summary.dropped[2].tau_s, 1000.0);
  EXPECT_EQ(summary.message, "3 taus dropped");
}

TEST(AllanFamily, TausWithTooFewTermsAreDroppedNamingTheCount) {
  const std::vector<double> y = TestRecord(1000, 4);
  AvarOptions options;
  options.statistic = Statistic::kAllanNonOverlapping;
  options.min_terms = 10;
  AvarSummary summary;
  ASSERT_TRUE(ComputeStatisticValues(options, y, &summary));
  // M - 1 terms: m = 64 has 14, m = 128 has 6, m = 256 has 2.
  EXPECT_EQ(summary.points.back().m, 64);
  ASSERT_EQ(summary.dropped.size(), 2u);
  EXPECT_EQ(summary.dropped[0].m, 128);
  EXPECT_EQ(summary.dropped[0].reason, "only 6 terms at m = 128, fewer than min_terms = 10");
  EXPECT_EQ(summary.dropped[1].m, 256);
}

TEST(AllanFamily, NothingLeftIsAFailure) {
  const std::vector<double> y = TestRecord(10, 4);
  AvarOptions options;
  options.min_terms = 100;
  AvarSummary summary;
  EXPECT_FALSE(ComputeStatisticValues(options, y, &summary));
  EXPECT_FALSE(summary.ok);
  EXPECT_TRUE(summary.points.empty());
  EXPECT_FALSE(summary.dropped.empty());
  EXPECT_NE(summary.message.find("no averaging time"), std::string::npos) << summary.message;
}

TEST(AllanFamily, RejectsBadInput) {
  AvarSummary summary;
  const std::vector<double> two = {1.0, 2.0};
  EXPECT_FALSE(ComputeStatisticValues(AvarOptions{}, two, &summary));
  EXPECT_EQ(summary.message, "need at least 3 rate samples, got 2");
  EXPECT_EQ(summary.num_samples, 2);

  std::vector<double> y = TestRecord(100, 5);
  y[17] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(ComputeStatisticValues(AvarOptions{}, y, &summary));
  EXPECT_EQ(summary.message, "rate sample 17 is not finite (nan)");
  y[17] = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(ComputeStatisticValues(AvarOptions{}, y, &summary));
  EXPECT_EQ(summary.message, "rate sample 17 is not finite (inf)");

  AvarOptions bad;
  bad.sample_clock = SampleClock::FromPeriodS(0.0);
  y[17] = 0.0;
  EXPECT_FALSE(ComputeStatisticValues(bad, y, &summary));
  EXPECT_EQ(summary.message.rfind("invalid options: sample period", 0), 0u) << summary.message;
  EXPECT_TRUE(summary.points.empty());
}

TEST(AllanFamily, AngleToRateDifferencesOverTheSamplePeriod) {
  const std::vector<double> angle = {1.0, 1.5, 3.0, 2.0};
  EXPECT_EQ(AngleToRate(angle, 0.5), (std::vector<double>{1.0, 3.0, -2.0}));
  EXPECT_TRUE(AngleToRate(std::vector<double>{1.0}, 1.0).empty());
  EXPECT_TRUE(AngleToRate({}, 1.0).empty());
}

}  // namespace
}  // namespace allanlab::estimators
