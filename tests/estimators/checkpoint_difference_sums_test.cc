// The overlapping sums on long records from checkpoints, in pieces shared by two threads, and fused
// with the integration into a stored phase: each has the bits of the stored phase's sums, in one
// thread and in two.
#include <gtest/gtest.h>
#include <omp.h>

#include <cstdint>
#include <random>
#include <thread>
#include <vector>

#include "estimators/difference_sums.h"
#include "estimators/phase_checkpoints.h"
#include "estimators/phase_integral.h"

namespace allanlab::estimators {
namespace {

TEST(CheckpointDifferenceSums, SameBitsAsTheStoredPhaseInOneAndTwoThreads) {
  // Long enough for the helper thread and for two tiers of long lags.
  const std::size_t n = (std::size_t{1} << 21) + 12345;
  std::mt19937_64 engine(3);
  std::normal_distribution<double> normal;
  std::vector<double> y(n);
  double walk = 0.0;
  for (double& v : y) {
    walk += 0.001 * normal(engine);
    v = 0.5 + normal(engine) + walk;
  }
  const double reference = ReferenceLevel(y);
  const PhaseCheckpoints x(y, reference);
  for (int order : {2, 3}) {
    std::vector<std::int64_t> ms;
    for (std::int64_t m = 1; order * m <= static_cast<std::int64_t>(n); m *= 2) ms.push_back(m);
    ASSERT_TRUE(FitsCheckpointPass(static_cast<std::int64_t>(n), order, ms));
    // The reference: the phase stored whole first, then its sums.
    std::vector<double> phase(n + 1), stored(ms.size());
    IntegrateAbout(y, reference, phase);
    OverlappingDifferenceSums(phase, order, ms, stored);
    const int before = omp_get_max_threads();
    for (int threads : {1, 2}) {
      omp_set_num_threads(threads);
      std::vector<double> sums(ms.size());
      ASSERT_TRUE(SumOverlappingDifferencesFromCheckpoints(x, order, ms, sums));
      EXPECT_EQ(sums, stored) << "order " << order << ", threads " << threads;
      // The fused pass.
      std::vector<double> fused_phase(n + 1), fused(ms.size());
      IntegrateAndSumOverlappingDifferences(y, reference, order, ms, fused_phase, fused);
      EXPECT_EQ(fused, stored) << "order " << order << ", threads " << threads;
      EXPECT_EQ(fused_phase, phase) << "order " << order << ", threads " << threads;
    }
    omp_set_num_threads(before);
  }
  // A dense grid's long lags do not suit the pass: nothing is computed.
  std::vector<double> sums(1);
  const std::vector<std::int64_t> odd = {40001};
  EXPECT_FALSE(FitsCheckpointPass(static_cast<std::int64_t>(n), 2, odd));
  EXPECT_FALSE(SumOverlappingDifferencesFromCheckpoints(x, 2, odd, sums));
}

}  // namespace
}  // namespace allanlab::estimators
