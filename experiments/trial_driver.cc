#include "experiments/trial_driver.h"

#include "sim/seeding.h"

namespace allanlab::experiments {

std::uint64_t PointSeed(std::uint64_t spec_seed, int point_index) {
  return sim::SplitMix64(sim::SplitMix64(spec_seed) ^ static_cast<std::uint64_t>(point_index));
}

}  // namespace allanlab::experiments
