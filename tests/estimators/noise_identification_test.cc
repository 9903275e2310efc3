// Identification from the integrated record keeps the m-averages of a tau for its passes, or
// recomputes them in every pass when there are too many to keep: both must give the same bits
// (exponent estimate and class), so that where the limit falls never shows in the output.
#include "estimators/noise_identification.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "estimators/phase_integral.h"

namespace allanlab::estimators {
namespace {

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(NoiseIdentificationAverages, StoredAndRecomputedGiveTheSameBits) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal;
  const std::size_t n = 200000;
  // White, random walk over white (differenced once or twice by the ACF), and a biased ramp.
  std::vector<std::vector<double>> records(3, std::vector<double>(n));
  double walk = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    records[0][i] = normal(rng);
    walk += 0.05 * normal(rng);
    records[1][i] = 0.1 * normal(rng) + walk;
    records[2][i] = 1e3 + 1e-6 * static_cast<double>(i) + normal(rng);
  }
  int compared = 0;
  for (const std::vector<double>& rate : records) {
    std::vector<double> phase(rate.size() + 1);
    IntegrateAbout(rate, ReferenceLevel(rate), phase);
    for (std::int64_t m : {1, 2, 3, 7, 16, 100, 1000, 5000}) {
      const NoiseId stored = IdentifyNoise(rate, phase, m);
      const std::size_t limit = SetMaxStoredAveragesForTesting(0);
      const NoiseId recomputed = IdentifyNoise(rate, phase, m);
      SetMaxStoredAveragesForTesting(limit);
      EXPECT_EQ(stored.alpha, recomputed.alpha) << "m " << m;
      EXPECT_EQ(stored.averages, recomputed.averages) << "m " << m;
      EXPECT_TRUE(SameBits(stored.estimate, recomputed.estimate))
          << "m " << m << ": " << stored.estimate << " vs " << recomputed.estimate;
      ++compared;
    }
  }
  EXPECT_EQ(compared, 24);
}

}  // namespace
}  // namespace allanlab::estimators
