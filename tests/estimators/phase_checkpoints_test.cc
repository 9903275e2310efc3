// The integrated record kept as checkpoints: every stretch rebuilt from them, at any alignment and
// up to the record's end, has the bits of one integration of the whole record; so do the sampled
// values identification reads, and the same pass taken in uneven steps.
#include "estimators/phase_checkpoints.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "estimators/phase_integral.h"

namespace allanlab::estimators {
namespace {

std::vector<double> Rate(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  std::normal_distribution<double> normal;
  std::vector<double> y(n);
  for (double& v : y) v = 0.25 + normal(engine);
  return y;
}

TEST(PhaseCheckpoints, RebuiltStretchesHaveTheWholeIntegralsBits) {
  const std::vector<double> y = Rate(20011, 1);  // N not a multiple of 8
  const double reference = ReferenceLevel(y);
  std::vector<double> whole(y.size() + 1);
  IntegrateAbout(y, reference, whole);
  const PhaseCheckpoints x(y, reference);
  const auto n = static_cast<std::int64_t>(y.size());
  EXPECT_EQ(x.Last(), whole.back());
  for (std::int64_t lo : {0, 1, 7, 8, 63, 64, 65, 1000, 19990, 20003, 20011}) {
    for (std::int64_t count : {1, 2, 7, 8, 9, 17, 64, 100, 4097}) {
      if (lo + count - 1 > n) continue;
      std::vector<double> out(static_cast<std::size_t>(count));
      x.Rebuild(lo, out);
      for (std::int64_t i = 0; i < count; ++i) {
        ASSERT_EQ(out[static_cast<std::size_t>(i)], whole[static_cast<std::size_t>(lo + i)]) << lo << " " << count << " " << i;
      }
    }
  }
}

TEST(PhaseCheckpoints, SampledValuesAndStepwisePassMatch) {
  const std::vector<double> y = Rate(50000, 2);
  const double reference = ReferenceLevel(y);
  std::vector<double> whole(y.size() + 1);
  IntegrateAbout(y, reference, whole);
  const PhaseCheckpoints x(y, reference);
  for (std::int64_t m : {1, 3, 32, 64, 128, 1000}) {
    for (std::int64_t first : {std::int64_t{0}, m * 7}) {
      const auto count = static_cast<std::size_t>((50000 - first) / m + 1);
      std::vector<double> sampled(count);
      x.Decimate(first, m, sampled);
      for (std::size_t k = 0; k < count; ++k) {
        ASSERT_EQ(sampled[k], whole[static_cast<std::size_t>(first) + k * static_cast<std::size_t>(m)]) << m;
      }
    }
  }
  PhaseCheckpoints steps(y, reference, PhaseCheckpoints::Deferred{});
  for (std::int64_t upto : {100, 4096, 4096, 9000, 30000, 60000}) steps.IntegrateUpTo(upto);
  ASSERT_TRUE(steps.complete());
  EXPECT_EQ(steps.Last(), x.Last());
  for (std::int64_t k = 0; k <= 50000; k += PhaseCheckpoints::kStride) EXPECT_EQ(steps.At(k), x.At(k)) << k;
}

}  // namespace
}  // namespace allanlab::estimators
