// A curve from the checkpoints of the integrated record (ComputeAvarFromCheckpoints, a workspace
// that keeps checkpoints only)
// against the one from the stored record (ComputeAvarOnStorage): identification, the record EDF
// and R(n) read rebuilt values, which must be the stored ones, so every point has the same bits.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "estimators/allan_family.h"
#include "estimators/avar.h"
#include "estimators/noise_identification.h"
#include "estimators/phase_checkpoints.h"
#include "estimators/phase_integral.h"

namespace allanlab::estimators {
namespace {

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// White FM, random walk FM, and white PM (differenced white noise: R(n) decides its alpha).
std::vector<double> Record(int kind, std::size_t n, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  std::normal_distribution<double> normal;
  std::vector<double> y(n);
  double walk = 0.0, previous = normal(engine);
  for (double& v : y) {
    const double e = normal(engine);
    walk += 1e-3 * e;
    v = kind == 0 ? 0.01 + e : kind == 1 ? walk : e - previous;
    previous = e;
  }
  return y;
}

void ExpectSameSummary(const AvarSummary& a, const AvarSummary& b, const char* what) {
  ASSERT_EQ(a.ok, b.ok) << what;
  EXPECT_EQ(a.message, b.message) << what;
  ASSERT_EQ(a.points.size(), b.points.size()) << what;
  for (std::size_t k = 0; k < a.points.size(); ++k) {
    const AvarPoint& p = a.points[k];
    const AvarPoint& q = b.points[k];
    EXPECT_TRUE(SameBits(p.value, q.value) && SameBits(p.edf, q.edf) && SameBits(p.ci_low, q.ci_low) &&
                SameBits(p.ci_high, q.ci_high) && p.alpha == q.alpha && p.alpha_identified == q.alpha_identified &&
                p.edf_from_record == q.edf_from_record && p.ci_from_distribution == q.ci_from_distribution)
        << what << ", m " << p.m;
  }
}

TEST(AvarCheckpoints, SameSummaryAsTheStoredRecord) {
  for (int kind : {0, 1, 2}) {
    for (std::int64_t cap : {std::int64_t{0}, std::int64_t{64}}) {
      const std::vector<double> y = Record(kind, 300000, 10 + static_cast<std::uint64_t>(kind));
      AvarOptions options;
      options.sample_clock = SampleClock::FromPeriodS(0.01);
      options.confidence_method = ConfidenceMethod::kAuto;
      options.identification_max_averages = cap;
      std::vector<double> storage(y.size() + 1);
      std::copy(y.begin(), y.end(), storage.begin() + 1);
      AvarSummary stored, adopted;
      ASSERT_TRUE(ComputeAvarOnStorage(options, storage, &stored)) << stored.message;
      ASSERT_TRUE(ComputeAvarFromCheckpoints(options, PhaseCheckpoints(y, ReferenceLevel(y)), &adopted));
      ExpectSameSummary(stored, adopted, "adopted");
      // The values alone, with checkpoints built by the pass itself.
      AllanFamilyWorkspace workspace;
      workspace.KeepCheckpointsOnly();
      AvarSummary values;
      ASSERT_TRUE(ComputeStatisticValues(options, y, &values, &workspace));
      ASSERT_NE(workspace.Checkpoints(), nullptr);
      ASSERT_EQ(values.points.size(), stored.points.size());
      for (std::size_t k = 0; k < values.points.size(); ++k) {
        EXPECT_TRUE(SameBits(values.points[k].value, stored.points[k].value)) << values.points[k].m;
      }
    }
  }
}

// The integrated record built in memory the caller supplies (ComputeAvar with `phase`: its pages
// faulted in by a helper thread in app/input/record_curve.cc): the summary of a buffer of its own,
// bit for bit; a buffer of the wrong size is not used.
TEST(AvarCheckpoints, CallersPhaseBufferGivesTheSameSummary) {
  for (int kind : {0, 1, 2}) {
    const std::vector<double> y = Record(kind, (std::size_t{1} << 20) + 3, 20 + static_cast<std::uint64_t>(kind));
    AvarOptions options;
    options.sample_clock = SampleClock::FromPeriodS(0.01);
    options.confidence_method = ConfidenceMethod::kAuto;
    AvarSummary own, supplied, wrong_size;
    ASSERT_TRUE(ComputeAvar(options, y, &own)) << own.message;
    std::vector<double> phase(y.size() + 1, -1.0);
    ASSERT_TRUE(ComputeAvar(options, y, &supplied, phase)) << supplied.message;
    ExpectSameSummary(own, supplied, "supplied phase");
    EXPECT_EQ(phase[0], 0.0);  // the integrated record is there
    EXPECT_NE(phase.back(), -1.0);
    std::vector<double> short_phase(y.size(), -1.0);
    ASSERT_TRUE(ComputeAvar(options, y, &wrong_size, short_phase));
    ExpectSameSummary(own, wrong_size, "wrong size");
    EXPECT_EQ(short_phase.back(), -1.0);
  }
}

TEST(AvarCheckpoints, ModifiedToAllanRatioFromCheckpointsHasTheStoredBits) {
  const std::vector<double> y = Record(2, 100003, 5);
  const double reference = ReferenceLevel(y);
  std::vector<double> phase(y.size() + 1);
  IntegrateAbout(y, reference, phase);
  const PhaseCheckpoints x(y, reference);
  for (std::int64_t m : {4, 100, 4096, 30000}) {
    EXPECT_TRUE(SameBits(ModifiedToAllanRatioOfCheckpoints(x, 0, 100003, m), ModifiedToAllanRatioOfPhase(phase, m)))
        << m;
    const std::span<const double> middle = std::span<const double>(phase).subspan(1000, 60001);
    EXPECT_TRUE(SameBits(ModifiedToAllanRatioOfCheckpoints(x, 1000, 60000, m), ModifiedToAllanRatioOfPhase(middle, m)))
        << m;
  }
}

}  // namespace
}  // namespace allanlab::estimators
