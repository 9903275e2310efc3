// ComputeAvar's own logic: confidence method per options, fixed vs identified alpha, the
// fallback where identification cannot run, angle input, and failures passed through.
#include "estimators/avar.h"

#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "estimators/allan_family.h"
#include "estimators/avar_options.h"
#include "estimators/confidence.h"
#include "estimators/estimate_distribution.h"
#include "tests/support/monte_carlo.h"

namespace allanlab::estimators {
namespace {

std::vector<double> WhiteRecord(std::int64_t n) {
  return testing_support::SingleTermModel(sim::WhiteRateNoise{1e-3}, 100.0).Generate(7, 0, n);
}

AvarOptions Options(ConfidenceMethod method) {
  AvarOptions options;
  options.sample_clock = SampleClock::FromPeriodS(0.01);
  options.confidence_method = method;
  return options;
}

// In place (ComputeAvarInPlace on a vector, ComputeAvarOnStorage behind a spare slot): the same
// summary as from a copy, for rate (with and without spare capacity)
// and angle input, the overlapping statistics (integrated in place) and MVAR (in place
// too, with its own work space); a record that overflows fails with the position.
TEST(ComputeAvar, InPlaceGivesTheSameSummary) {
  const std::vector<double> rate = WhiteRecord(70001);
  std::vector<double> angle(rate.size() + 1, 0.0);
  for (std::size_t k = 0; k < rate.size(); ++k) angle[k + 1] = angle[k] + rate[k] * 0.01;
  for (Statistic st : {Statistic::kAllanOverlapping, Statistic::kHadamardOverlapping,
                       Statistic::kModifiedAllan}) {
    for (InputKind input : {InputKind::kRate, InputKind::kAngle}) {
      AvarOptions options = Options(ConfidenceMethod::kGreenhallRiley);
      options.statistic = st;
      options.input = input;
      const std::vector<double>& data = input == InputKind::kRate ? rate : angle;
      AvarSummary copy, in_place;
      ASSERT_TRUE(ComputeAvar(options, data, &copy)) << copy.message;
      std::vector<double> consumed;
      consumed.reserve(data.size() + 1);
      consumed.assign(data.begin(), data.end());
      ASSERT_TRUE(ComputeAvarInPlace(options, &consumed, &in_place)) << in_place.message;
      std::vector<double> storage(1, -7.0);  // the spare slot: its value must not matter
      storage.insert(storage.end(), data.begin(), data.end());
      AvarSummary on_storage;
      ASSERT_TRUE(ComputeAvarOnStorage(options, storage, &on_storage)) << on_storage.message;
      for (const AvarSummary* other : {&in_place, &on_storage}) {
        ASSERT_EQ(copy.points.size(), other->points.size());
        for (std::size_t k = 0; k < copy.points.size(); ++k) {
          SCOPED_TRACE("m=" + std::to_string(copy.points[k].m));
          EXPECT_EQ(copy.points[k].value, other->points[k].value);
          EXPECT_EQ(copy.points[k].alpha, other->points[k].alpha);
          EXPECT_EQ(copy.points[k].edf, other->points[k].edf);
        }
        EXPECT_EQ(copy.message, other->message);
      }
    }
  }
  std::vector<double> tight = rate;  // no spare capacity: grows once
  AvarSummary s;
  EXPECT_TRUE(ComputeAvarInPlace(Options(ConfidenceMethod::kSimple), &tight, &s)) << s.message;
  std::vector<double> none;
  EXPECT_FALSE(ComputeAvarOnStorage(Options(ConfidenceMethod::kSimple), none, &s));
  std::vector<double> huge(100, 1.5e308);  // mean ~0, so the running sum about it overflows
  for (std::size_t k = 50; k < huge.size(); ++k) huge[k] = -1.5e308;
  EXPECT_FALSE(ComputeAvarInPlace(Options(ConfidenceMethod::kSimple), &huge, &s));
  EXPECT_NE(s.message.find("overflows"), std::string::npos) << s.message;
}

TEST(ComputeAvar, GreenhallRileyIntervalPerPoint) {
  const std::vector<double> rate = WhiteRecord(4096);
  AvarSummary s;
  ASSERT_TRUE(ComputeAvar(Options(ConfidenceMethod::kGreenhallRiley), rate, &s)) << s.message;
  ASSERT_FALSE(s.points.empty());
  for (const AvarPoint& p : s.points) {
    SCOPED_TRACE("m=" + std::to_string(p.m));
    EXPECT_EQ(p.edf, StatisticEdf(Statistic::kAllanOverlapping, p.alpha, p.m, 4096, 0.01));
    const Interval i = ChiSquareInterval(p.value, p.edf, 0.683);
    EXPECT_EQ(p.ci_low, i.low);
    EXPECT_EQ(p.ci_high, i.high);
    EXPECT_LT(p.ci_low, p.value);
    EXPECT_GT(p.ci_high, p.value);
  }
  EXPECT_EQ(s.points.front().alpha, 0);  // white rate noise, thousands of averages
  EXPECT_TRUE(s.points.front().alpha_identified);
}

TEST(ComputeAvar, SimpleMethodUsesClustersMinusOne) {
  const std::vector<double> rate = WhiteRecord(1000);
  AvarSummary s;
  ASSERT_TRUE(ComputeAvar(Options(ConfidenceMethod::kSimple), rate, &s)) << s.message;
  for (const AvarPoint& p : s.points) {
    EXPECT_EQ(p.edf, static_cast<double>(1000 / p.m - 1)) << "m=" << p.m;
    EXPECT_EQ(p.ci_low, ChiSquareInterval(p.value, p.edf, 0.683).low);
  }
  EXPECT_NE(s.message.find("simple formula"), std::string::npos) << s.message;
}

TEST(ComputeAvar, NoIntervalWhenNotAsked) {
  AvarSummary s;
  ASSERT_TRUE(ComputeAvar(Options(ConfidenceMethod::kNone), WhiteRecord(1000), &s));
  for (const AvarPoint& p : s.points) {
    EXPECT_EQ(p.edf, 0.0);
    EXPECT_EQ(p.ci_low, 0.0);
    EXPECT_EQ(p.ci_high, 0.0);
  }
}

TEST(ComputeAvar, FixedAlphaIsUsedAndNotMarkedIdentified) {
  AvarOptions options = Options(ConfidenceMethod::kGreenhallRiley);
  options.alpha_fixed = true;
  options.alpha = -2;
  AvarSummary s;
  ASSERT_TRUE(ComputeAvar(options, WhiteRecord(1000), &s));
  for (const AvarPoint& p : s.points) {
    EXPECT_EQ(p.alpha, -2);
    EXPECT_FALSE(p.alpha_identified);
    EXPECT_EQ(p.edf, StatisticEdf(Statistic::kAllanOverlapping, -2, p.m, 1000, 0.01));
  }
}

// kAuto at <= 16 clusters holds the shorter tau's exponent (the reading there scatters by a step):
// the point must not claim it was identified at its own tau, or the table shows a held value as
// a measured one.
TEST(ComputeAvar, ExponentHeldAtFewClustersIsNotMarkedIdentified) {
  const std::int64_t n = 6000;
  AvarSummary s;
  ASSERT_TRUE(ComputeAvar(Options(ConfidenceMethod::kAuto), WhiteRecord(n), &s)) << s.message;
  int held = 0;
  for (std::size_t k = 0; k < s.points.size(); ++k) {
    const AvarPoint& p = s.points[k];
    SCOPED_TRACE("m=" + std::to_string(p.m));
    if (k > 0 && n / p.m <= kDistributionIntervalMaxClusters) {
      EXPECT_FALSE(p.alpha_identified);
      EXPECT_EQ(p.alpha, s.points[k - 1].alpha);
      ++held;
    } else if (n / p.m >= kSteadyIdentificationAverages) {
      EXPECT_TRUE(p.alpha_identified);
    }
  }
  EXPECT_GE(held, 1);
}

// TOTVAR reaches m = n - 1, where fewer than three m-averages exist: the last identified alpha
// carries over, the point says it was not identified and the summary says why.
TEST(ComputeAvar, UnidentifiableTausInheritTheShorterTausAlpha) {
  AvarOptions options = Options(ConfidenceMethod::kGreenhallRiley);
  options.statistic = Statistic::kTotal;
  options.taus.kind = TauGridKind::kExplicit;
  options.taus.explicit_taus_s = {0.16, 4.0};  // m = 16 and 400 of 1000
  AvarSummary s;
  ASSERT_TRUE(ComputeAvar(options, WhiteRecord(1000), &s)) << s.message;
  ASSERT_EQ(s.points.size(), 2u);
  EXPECT_TRUE(s.points[0].alpha_identified);
  EXPECT_FALSE(s.points[1].alpha_identified);
  EXPECT_EQ(s.points[1].alpha, s.points[0].alpha);
  EXPECT_GT(s.points[1].edf, 0.0);
  EXPECT_NE(s.message.find("not identifiable"), std::string::npos) << s.message;
}

TEST(ComputeAvar, AngleInputEqualsItsRate) {
  const std::vector<double> rate = WhiteRecord(1000);
  std::vector<double> angle(rate.size() + 1, 0.0);
  for (std::size_t k = 0; k < rate.size(); ++k) angle[k + 1] = angle[k] + rate[k] * 0.01;
  AvarOptions options = Options(ConfidenceMethod::kGreenhallRiley);
  AvarSummary from_rate, from_angle;
  ASSERT_TRUE(ComputeAvar(options, rate, &from_rate));
  options.input = InputKind::kAngle;
  ASSERT_TRUE(ComputeAvar(options, angle, &from_angle));
  EXPECT_EQ(from_angle.num_samples, 1000);
  ASSERT_EQ(from_angle.points.size(), from_rate.points.size());
  for (std::size_t i = 0; i < from_rate.points.size(); ++i) {
    EXPECT_NEAR(from_angle.points[i].value, from_rate.points[i].value,
                1e-9 * from_rate.points[i].value);
    EXPECT_EQ(from_angle.points[i].alpha, from_rate.points[i].alpha);
    EXPECT_EQ(from_angle.points[i].edf, from_rate.points[i].edf);
  }
}

TEST(ComputeAvar, BadDataOrOptionsFailWithAMessage) {
  std::vector<double> rate = WhiteRecord(100);
  rate[50] = std::numeric_limits<double>::quiet_NaN();
  AvarSummary s;
  EXPECT_FALSE(ComputeAvar(Options(ConfidenceMethod::kGreenhallRiley), rate, &s));
  EXPECT_FALSE(s.ok);
  EXPECT_FALSE(s.message.empty());
  AvarOptions bad = Options(ConfidenceMethod::kGreenhallRiley);
  bad.confidence = 1.5;
  EXPECT_FALSE(ComputeAvar(bad, WhiteRecord(100), &s));
  EXPECT_FALSE(s.message.empty());
}

}  // namespace
}  // namespace allanlab::estimators
