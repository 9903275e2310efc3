// `avar`'s default intervals (ConfidenceMethod::kAuto, the AvarOptions default) on records made
// apart from sim/ (experiments/plain_noise.h), against the exact expectation of those records.
// Trials: 1500 per case (8000 at few clusters); the binomial standard error of a 68.3 % coverage is 1.20 points and of a
// 95 % one 0.56 points; tolerances are 3.3 standard errors (false-fail rate 0.1 % per check).
// The Greenhall-Riley intervals at the per-tau noise type (the default before) covered 0.631 and
// 0.876 (white, m = N/32) and 0.750 and 0.978 (point-sampled random walk, m = 1) in 2000 trials:
// 4-13 standard errors off, so these checks fail on them.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "estimators/avar.h"
#include "estimators/confidence.h"
#include "estimators/record_edf.h"
#include "experiments/plain_noise.h"

namespace allanlab::estimators {
namespace {

using experiments::GeneratePlain;
using experiments::PlainExpectedAvar;
using experiments::PlainNoise;

constexpr int kTrials = 1500;
// At few clusters chi-square(EDF) itself misses by 1-3 points: the checks there need the
// smaller binomial error of more trials to be able to fail (see FewClusters below).
constexpr int kFewClusterTrials = 8000;
constexpr std::int64_t kSamples = 4096;

struct Coverage {
  double at68 = 0.0, at95 = 0.0;
};

Coverage DefaultCoverage(PlainNoise noise, std::int64_t m, ConfidenceMethod method,
                         std::uint64_t seed, int trials = kTrials) {
  const double expected = PlainExpectedAvar(noise, m);
  int in68 = 0, in95 = 0;
  for (int trial = 0; trial < trials; ++trial) {
    AvarOptions options;
    options.confidence_method = method;
    options.taus.kind = TauGridKind::kOctave;
    AvarSummary summary;
    const std::vector<double> record = GeneratePlain(noise, kSamples, seed, trial);
    EXPECT_TRUE(ComputeAvar(options, record, &summary)) << summary.message;
    for (const AvarPoint& p : summary.points) {
      if (p.m != m) continue;
      const Interval a = PointInterval(summary, p, 0.683);
      const Interval b = PointInterval(summary, p, 0.95);
      in68 += a.low <= expected && expected <= a.high;
      in95 += b.low <= expected && expected <= b.high;
    }
  }
  return {static_cast<double>(in68) / trials, static_cast<double>(in95) / trials};
}

void ExpectNominal(const Coverage& c, int trials = kTrials) {
  const double se68 = std::sqrt(0.683 * 0.317 / trials), se95 = std::sqrt(0.95 * 0.05 / trials);
  EXPECT_NEAR(c.at68, 0.683, 3.3 * se68);
  EXPECT_NEAR(c.at95, 0.95, 3.3 * se95);
}

// At m = N/32 the lag-1 ACF sees 32 averages: one white record in 15 read as phase noise, whose
// Greenhall-Riley EDF is 2-4 times too large.
TEST(DefaultIntervalCoverage, WhiteAtThirtyTwoClusters) {
  ExpectNominal(DefaultCoverage(PlainNoise::kWhite, kSamples / 32, ConfidenceMethod::kAuto, 11));
}

// At m = 1 the Allan differences of a point-sampled random walk are independent (EDF = N - 1),
// where Greenhall-Riley's averaged continuous walk has 24 % fewer.
TEST(DefaultIntervalCoverage, PointSampledRandomWalkAtShortestTau) {
  ExpectNominal(DefaultCoverage(PlainNoise::kRandomWalk, 1, ConfidenceMethod::kAuto, 12));
}

// The same record family averaged over each sample interval has 11 % fewer EDF at m = 1; the
// measured EDF follows it.
TEST(DefaultIntervalCoverage, AveragedRandomWalkAtShortestTau) {
  ExpectNominal(DefaultCoverage(PlainNoise::kRandomWalkAveraged, 1, ConfidenceMethod::kAuto, 13));
}

// White noise at m = 1: Allan differences y_{k+1} - y_k, lag-1 correlation -1/2.
TEST(DefaultIntervalCoverage, WhiteAtShortestTau) {
  ExpectNominal(DefaultCoverage(PlainNoise::kWhite, 1, ConfidenceMethod::kAuto, 14));
}

// At 8 clusters (m = N/8) chi-square at the right EDF (9.7 for white rate noise) covered 0.711
// and 0.961 (default_intervals table, 20000 trials): the estimate is a weighted sum of
// chi-square(1) variables with a lighter lower tail than chi-square(9.7). With 8000 trials the
// tolerances are 1.7 and 0.8 points, so these checks fail on chi-square(EDF) intervals.
TEST(DefaultIntervalCoverage, WhiteAtEightClusters) {
  ExpectNominal(DefaultCoverage(PlainNoise::kWhite, kSamples / 8, ConfidenceMethod::kAuto, 15,
                                kFewClusterTrials),
                kFewClusterTrials);
}

TEST(DefaultIntervalCoverage, AveragedRandomWalkAtEightClusters) {
  ExpectNominal(DefaultCoverage(PlainNoise::kRandomWalkAveraged, kSamples / 8,
                                ConfidenceMethod::kAuto, 16, kFewClusterTrials),
                kFewClusterTrials);
}

// The closed-form EDF of OAVAR for a process whose Allan differences are sum_i c_i w_{t+i} with
// iid w: M / (1 + 2 sum_k (1 - k/M) rho_k^2), rho_k the normalised autocorrelation of c.
double KernelEdf(const std::vector<double>& c, std::int64_t big_m) {
  const auto len = static_cast<std::int64_t>(c.size());
  double r0 = 0.0;
  for (double v : c) r0 += v * v;
  double sum = 1.0;
  for (std::int64_t k = 1; k < len; ++k) {
    double r = 0.0;
    for (std::int64_t i = 0; i + k < len; ++i) r += c[i] * c[i + k];
    sum += 2.0 * (1.0 - static_cast<double>(k) / big_m) * (r / r0) * (r / r0);
  }
  return static_cast<double>(big_m) / sum;
}

std::vector<double> Phase(const std::vector<double>& rate) {
  std::vector<double> x(rate.size() + 1, 0.0);
  for (std::size_t i = 0; i < rate.size(); ++i) x[i + 1] = x[i] + rate[i];
  return x;
}

// RecordEdf averaged over 60 records against the closed form: white (box kernel -1..-1, 1..1) and
// the point-sampled random walk (triangle 1, 2, .., m, .., 1). The per-record scatter of RecordEdf
// is a few percent, so the mean of 60 is within 1.5 % with a wide margin.
TEST(RecordEdf, MatchesClosedFormOnWhiteAndRandomWalk) {
  for (std::int64_t m : {1, 4, 16}) {
    const std::int64_t big_m = kSamples - 2 * m + 1;
    std::vector<double> box(2 * m, 1.0), triangle;
    for (std::int64_t i = 0; i < m; ++i) box[i] = -1.0;
    for (std::int64_t i = 1; i <= m; ++i) triangle.push_back(static_cast<double>(i));
    for (std::int64_t i = m - 1; i >= 1; --i) triangle.push_back(static_cast<double>(i));
    struct Case {
      PlainNoise noise;
      const std::vector<double>* kernel;
    };
    for (const Case& c : {Case{PlainNoise::kWhite, &box}, Case{PlainNoise::kRandomWalk, &triangle}}) {
      double mean = 0.0;
      for (int trial = 0; trial < 60; ++trial) {
        mean += RecordEdf(Statistic::kAllanOverlapping,
                          Phase(GeneratePlain(c.noise, kSamples, 21, trial)), m) / 60.0;
      }
      const double exact = KernelEdf(*c.kernel, big_m);
      EXPECT_NEAR(mean / exact, 1.0, 0.015) << "m=" << m << " exact " << exact;
    }
  }
}

// On records far longer than the cap, RecordEdf reads kRecordEdfMaxTerms differences from the
// middle: each record's value against the closed form at the longest lag windows (m = 32 .. 128,
// 64 .. 256 lags), where the cap's scatter is largest. Measured (24 records of 2^20 samples per
// noise, this seed): mean of value / closed form - 1 within +-0.007 at every m; per-record
// standard deviation 0.029 (m = 32), 0.034-0.046 (64), 0.058-0.063 (128), which moves a 68.3 %
// interval's half-width by a third of that and its coverage by well under a point. The bounds:
// |mean| <= 0.04 (three standard errors of 24 records at 0.065) and rms <= 0.09 (the rms of 24
// records has a relative standard error near 15 %); a cap of 2^13 terms, with twice the scatter,
// fails the second.
TEST(RecordEdf, CappedTermsMatchClosedFormOnLongRecords) {
  constexpr std::int64_t kLong = std::int64_t{1} << 20;
  constexpr int kRecords = 24;
  for (PlainNoise noise : {PlainNoise::kWhite, PlainNoise::kRandomWalk}) {
    for (std::int64_t m : {32, 64, 128}) {
      std::vector<double> kernel;
      if (noise == PlainNoise::kWhite) {
        kernel.assign(2 * m, 1.0);
        for (std::int64_t i = 0; i < m; ++i) kernel[i] = -1.0;
      } else {
        for (std::int64_t i = 1; i <= m; ++i) kernel.push_back(static_cast<double>(i));
        for (std::int64_t i = m - 1; i >= 1; --i) kernel.push_back(static_cast<double>(i));
      }
      const double exact = KernelEdf(kernel, kLong - 2 * m + 1);
      double sum = 0.0, sum_squares = 0.0;
      for (int trial = 0; trial < kRecords; ++trial) {
        const std::vector<double> phase = Phase(GeneratePlain(noise, kLong, 23, trial));
        const double error = RecordEdf(Statistic::kAllanOverlapping, phase, m) / exact - 1.0;
        sum += error;
        sum_squares += error * error;
      }
      const double mean = sum / kRecords, rms = std::sqrt(sum_squares / kRecords);
      EXPECT_LE(std::abs(mean), 0.04) << "noise " << static_cast<int>(noise) << " m=" << m;
      EXPECT_LE(rms, 0.09) << "noise " << static_cast<int>(noise) << " m=" << m;
    }
  }
}

TEST(RecordEdf, UnavailableWhereTheLagWindowIsLong) {
  EXPECT_TRUE(RecordEdfAvailable(Statistic::kAllanOverlapping, 64, 4096));
  EXPECT_FALSE(RecordEdfAvailable(Statistic::kAllanOverlapping, 128, 4096));
  EXPECT_FALSE(RecordEdfAvailable(Statistic::kModifiedAllan, 1, 4096));
  EXPECT_FALSE(RecordEdfAvailable(Statistic::kTotal, 1, 4096));
  EXPECT_EQ(RecordEdf(Statistic::kAllanOverlapping, Phase(std::vector<double>(100, 1.0)), 64), 0.0);
}

}  // namespace
}  // namespace allanlab::estimators
