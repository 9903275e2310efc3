// The overlapping AVAR moments read the phase variogram as exact double pairs (SplitVariogram),
// whose second differences are formed in double-double arithmetic: on these models the same bits
// as forming them from the long doubles (which round three times at 64 bits, so could differ in a
// difference's last bit). Scratch memory reused across m (MomentScratch) changes no bit.
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "estimators/exact_avar_variance.h"
#include "estimators/exact_edf.h"

namespace allanlab::estimators {
namespace {

// A diagnosis-like model: white, flicker, random walk and a Gauss-Markov bump (V grows like k^3
// and the flicker autocovariance has its long-double harmonic sums).
sim::SensorModel MixedModel() {
  sim::SensorModel model;
  model.sample_clock = SampleClock::FromRateHz(100.0);
  model.terms.push_back(sim::WhiteRateNoise{.arw_rad_per_sqrt_s = 4.4e-5});
  model.terms.push_back(sim::FlickerNoise{.bias_instability_rad_per_s = 3.6e-6});
  model.terms.push_back(sim::RandomWalkRate{.rrw_rad_per_s_per_sqrt_s = 1.2e-8});
  model.terms.push_back(sim::GaussMarkov{.sigma_rad_per_s = 1.5e-5, .correlation_time_s = 60.0});
  return model;
}

TEST(SplitVariogram, PairsAddUpToTheLongDoubles) {
  const std::int64_t n = 50001;
  const std::vector<double> r = MixedModel().GaussianAutocovariance(n + 1);
  const std::vector<long double> v = PhaseVariogram(r, n + 1);
  const SplitVariogram split = SplitPhaseVariogram(v);
  ASSERT_EQ(split.hi.size(), v.size());
  for (std::size_t j = 0; j < v.size(); ++j) {
    ASSERT_EQ(static_cast<long double>(split.hi[j]) + split.lo[j], v[j]) << j;
  }
}

TEST(SplitVariogram, SameMomentsBitsAsTheLongDoubles) {
  const sim::SensorModel model = MixedModel();
  for (std::int64_t n : {4097, 50001}) {
    const sim::RecordShape shape{n, sim::AvarEstimatorKind::kOverlapping};
    std::vector<std::int64_t> ms;
    for (std::int64_t m = 1; m <= n / 2; m = m * 5 / 4 + 1) ms.push_back(m);
    ms.push_back(n / 2);
    const std::vector<AvarMoments> shared = ModelAvarMoments(model, ms, shape);  // split
    const std::vector<double> r = model.GaussianAutocovariance(n + 2 * ms.back());
    const std::vector<long double> v = PhaseVariogram(r, n + 1);
    for (std::size_t i = 0; i < ms.size(); ++i) {
      const AvarMoments plain = ExactAvarMomentsFromVariogram(v, ms[i], shape);
      EXPECT_EQ(shared[i].mean, plain.mean) << "n " << n << " m " << ms[i];
      EXPECT_EQ(shared[i].variance, plain.variance) << "n " << n << " m " << ms[i];
    }
  }
}

TEST(SplitVariogram, SameHadamardMomentsBitsAsTheLongDoubles) {
  const std::int64_t n = 50001;
  const std::vector<double> r = MixedModel().GaussianAutocovariance(n + 1);
  const std::vector<long double> v = PhaseVariogram(r, n + 1);
  const SplitVariogram split = SplitPhaseVariogram(v);
  ASSERT_FALSE(split.hi.empty());
  for (std::int64_t m = 1; 3 * m <= n; m = m * 3 / 2 + 1) {
    const AvarMoments from_split = ExactOhvarMomentsFromVariogram(v, split, m, n);
    const AvarMoments plain = ExactOhvarMomentsFromVariogram(v, m, n);
    EXPECT_EQ(from_split.mean, plain.mean) << "OHVAR m " << m;
    EXPECT_EQ(from_split.variance, plain.variance) << "OHVAR m " << m;
  }
}

// One scratch through a grid of m, largest first (a later, shorter sum then finds the longer
// sums' values in the buffers: it must write every element it reads) and smallest first, against
// each m with no scratch: OAVAR (whole record and a half, as the halves view) and OHVAR.
TEST(SplitVariogram, ReusedScratchGivesTheSameBitsInAnyOrder) {
  const std::int64_t n = 50001;
  const std::vector<double> r = MixedModel().GaussianAutocovariance(n + 1);
  const std::vector<long double> v = PhaseVariogram(r, n + 1);
  const SplitVariogram split = SplitPhaseVariogram(v);
  std::vector<std::int64_t> ms;
  for (std::int64_t m = 1; 3 * m <= n; m = m * 3 / 2 + 1) ms.push_back(m);
  for (const bool largest_first : {true, false}) {
    MomentScratch scratch;
    for (std::size_t k = 0; k < ms.size(); ++k) {
      const std::int64_t m = largest_first ? ms[ms.size() - 1 - k] : ms[k];
      for (const std::int64_t length : {n, n / 2}) {
        const sim::RecordShape shape{length, sim::AvarEstimatorKind::kOverlapping};
        if (2 * m > length) continue;
        const AvarMoments reused = ExactAvarMomentsFromVariogram(v, split, m, shape, &scratch);
        const AvarMoments fresh = ExactAvarMomentsFromVariogram(v, split, m, shape);
        EXPECT_EQ(reused.mean, fresh.mean) << "m " << m << " N " << length;
        EXPECT_EQ(reused.variance, fresh.variance) << "m " << m << " N " << length;
      }
      const AvarMoments reused = ExactOhvarMomentsFromVariogram(v, m, n, &scratch);
      const AvarMoments fresh = ExactOhvarMomentsFromVariogram(v, m, n);
      EXPECT_EQ(reused.mean, fresh.mean) << "OHVAR m " << m;
      EXPECT_EQ(reused.variance, fresh.variance) << "OHVAR m " << m;
    }
  }
}

// A value that does not split exactly (beyond double's range, or not finite) leaves the split
// empty, and the moments are then read from the long doubles.
TEST(SplitVariogram, UnsplittableValuesLeaveItEmpty) {
  std::vector<long double> v = {0.0L, 1.0L, 3.0L, 6.0L};
  EXPECT_FALSE(SplitPhaseVariogram(v).hi.empty());
  v[2] = std::numeric_limits<long double>::max();
  EXPECT_TRUE(SplitPhaseVariogram(v).hi.empty());
  v[2] = std::numeric_limits<long double>::quiet_NaN();
  EXPECT_TRUE(SplitPhaseVariogram(v).hi.empty());
  const sim::RecordShape shape{3, sim::AvarEstimatorKind::kOverlapping};
  const AvarMoments plain = ExactAvarMomentsFromVariogram(v, 1, shape);
  const AvarMoments via_empty = ExactAvarMomentsFromVariogram(v, SplitPhaseVariogram(v), 1, shape);
  EXPECT_TRUE(std::isnan(plain.variance) && std::isnan(via_empty.variance));
}

}  // namespace
}  // namespace allanlab::estimators
