// On long records ComputeAvar measures every tau (noise identification, the record's EDF) in this
// thread and a helper: the summary must be the one a single thread gives, bit for bit, and each
// record-EDF point must carry RecordEdf measured directly on the integrated record.
#include <gtest/gtest.h>
#include <omp.h>

#include <cstring>
#include <random>
#include <thread>
#include <vector>

#include "estimators/avar.h"
#include "estimators/phase_integral.h"
#include "estimators/record_edf.h"

namespace allanlab::estimators {
namespace {

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

AvarSummary SummaryWithThreads(const std::vector<double>& rate, int threads) {
  const int before = omp_get_max_threads();
  omp_set_num_threads(threads);
  AvarOptions options;
  options.sample_clock = SampleClock::FromPeriodS(0.01);
  options.confidence_method = ConfidenceMethod::kAuto;  // what `avar` uses by default
  AvarSummary summary;
  EXPECT_TRUE(ComputeAvar(options, rate, &summary)) << summary.message;
  omp_set_num_threads(before);
  return summary;
}

TEST(AvarTauMeasures, TwoThreadsGiveTheOneThreadSummary) {
  if (std::thread::hardware_concurrency() < 2) GTEST_SKIP() << "one core";
  // White noise with a random walk under it: identification reads different exponents across taus.
  std::mt19937_64 rng(21);
  std::normal_distribution<double> normal;
  std::vector<double> rate(std::size_t{3} << 20);
  double walk = 0.0;
  for (double& y : rate) {
    walk += 2e-6 * normal(rng);
    y = 0.01 + 1e-4 * normal(rng) + walk;
  }
  const AvarSummary one = SummaryWithThreads(rate, 1);
  const AvarSummary two = SummaryWithThreads(rate, 2);
  ASSERT_EQ(one.points.size(), two.points.size());
  std::vector<double> phase(rate.size() + 1);
  IntegrateAbout(rate, ReferenceLevel(rate), phase);
  int from_record = 0;
  for (std::size_t k = 0; k < one.points.size(); ++k) {
    const AvarPoint& a = one.points[k];
    const AvarPoint& b = two.points[k];
    EXPECT_EQ(a.alpha, b.alpha) << a.m;
    EXPECT_EQ(a.alpha_identified, b.alpha_identified) << a.m;
    EXPECT_EQ(a.edf_from_record, b.edf_from_record) << a.m;
    EXPECT_TRUE(SameBits(a.value, b.value) && SameBits(a.edf, b.edf) && SameBits(a.ci_low, b.ci_low) &&
                SameBits(a.ci_high, b.ci_high))
        << "m " << a.m;
    if (b.edf_from_record) {
      ++from_record;
      EXPECT_TRUE(SameBits(b.edf, RecordEdf(Statistic::kAllanOverlapping, phase, b.m))) << "m " << b.m;
    }
  }
  EXPECT_GT(from_record, 3);
}

}  // namespace
}  // namespace allanlab::estimators
