// The shared flicker stream (GenerateOptions::flicker_cache, sim/flicker_stream_cache.h): models
// generated with one flicker seed share their flicker record whatever their own seeds, and a
// record is the same, bit for bit, whether its flicker record was kept, reused or left out for the
// budget.
#include <gtest/gtest.h>

#include <vector>

#include "sim/sensor_model.h"

namespace allanlab::sim {
namespace {

SensorModel FlickerModel(std::vector<NoiseTerm> terms, bool band_limited) {
  SensorModel model;
  model.sample_clock = SampleClock::FromRateHz(100.0);
  model.terms = std::move(terms);
  if (band_limited) model.band_limit = {LowPassKind::kFirstOrder, 30.0, 8, OutputSampling::kAverage};
  return model;
}

TEST(FlickerStreamCache, AKeptRecordGivesTheSameBitsAsAFreshOne) {
  constexpr std::int64_t kSamples = 5000;
  for (bool band_limited : {false, true}) {
    FlickerStreamCache warm(std::size_t{1} << 20);
    const GenerateOptions kept{.white_per_output_period = true, .flicker_cache = &warm, .flicker_seed = 11};
    for (double b : {0.002, 0.005}) {  // the second B reuses the first one's kept records
      const SensorModel model =
          FlickerModel({WhiteRateNoise{0.01}, FlickerNoise{b}, RandomWalkRate{0.001}}, band_limited);
      for (std::uint64_t trial = 0; trial < 3; ++trial) {
        FlickerStreamCache cold(std::size_t{1} << 20);
        const GenerateOptions fresh{.white_per_output_period = true, .flicker_cache = &cold, .flicker_seed = 11};
        EXPECT_EQ(model.Generate(7, trial, kSamples, kept), model.Generate(7, trial, kSamples, fresh))
            << "B " << b << " trial " << trial;
      }
    }
    const std::uint64_t shared = SensorModel::kSharedFlickerStream;
    EXPECT_NE(warm.Find(StreamSeed(11, 2, shared), kSamples), nullptr);
    EXPECT_EQ(warm.Find(StreamSeed(11, 3, shared), kSamples), nullptr);  // never drawn
  }
}

// Flicker alone, B and 2B, different seeds, one flicker seed: the records are exactly 2x apart
// (the FFT length is a power of two, so both scales are exact); without the cache they are not.
TEST(FlickerStreamCache, ModelsWithOneFlickerSeedShareTheRecord) {
  constexpr std::int64_t kSamples = 4096;
  FlickerStreamCache cache(std::size_t{1} << 20);
  const GenerateOptions shared{.flicker_cache = &cache, .flicker_seed = 5};
  const std::vector<double> one = FlickerModel({FlickerNoise{0.003}}, false).Generate(1, 0, kSamples, shared);
  const std::vector<double> two = FlickerModel({FlickerNoise{0.006}}, false).Generate(2, 0, kSamples, shared);
  for (std::int64_t k = 0; k < kSamples; ++k) ASSERT_EQ(two[k], 2.0 * one[k]) << k;
  const std::vector<double> own = FlickerModel({FlickerNoise{0.006}}, false).Generate(2, 0, kSamples);
  EXPECT_NE(own, two);
}

TEST(FlickerStreamCache, KeepsNoMoreThanItsBudget) {
  constexpr std::int64_t kSamples = 4096;
  FlickerStreamCache cache(kSamples * sizeof(double));  // room for one record
  const GenerateOptions kept{.flicker_cache = &cache, .flicker_seed = 3};
  const SensorModel model = FlickerModel({WhiteRateNoise{0.01}, FlickerNoise{0.002}}, false);
  for (std::uint64_t trial = 0; trial < 2; ++trial) {
    FlickerStreamCache cold(std::size_t{1} << 20);
    const GenerateOptions fresh{.flicker_cache = &cold, .flicker_seed = 3};
    EXPECT_EQ(model.Generate(7, trial, kSamples, kept), model.Generate(7, trial, kSamples, fresh));
  }
  const std::uint64_t shared = SensorModel::kSharedFlickerStream;
  EXPECT_NE(cache.Find(StreamSeed(3, 0, shared), kSamples), nullptr);
  EXPECT_EQ(cache.Find(StreamSeed(3, 1, shared), kSamples), nullptr);
}

}  // namespace
}  // namespace allanlab::sim
