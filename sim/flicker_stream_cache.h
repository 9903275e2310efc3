#pragma once
// Kasdin flicker records of unit innovation kept across Monte Carlo runs that draw their flicker
// from the same stream (GenerateOptions::flicker_cache: the envelopes of a diagnosis's models share
// one flicker record per trial, docs/theory.md §6.1; a flicker term's record is B times the unit
// one, §2.5.1). The FFT synthesis is the dearest part of a simulated record; a kept record is reused
// bit for bit, so results do not depend on which run computed it first. Thread-safe; holds at most a
// byte budget (later records are computed and not kept).
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

namespace allanlab::sim {

class FlickerStreamCache {
 public:
  explicit FlickerStreamCache(std::size_t budget_bytes) : budget_bytes_(budget_bytes) {}

  // The kept record of `n` samples drawn from the stream seeded `stream_seed` (StreamSeed), or
  // nullptr.
  std::shared_ptr<const std::vector<double>> Find(std::uint64_t stream_seed, std::size_t n) const;
  // Keeps `unit` for (stream_seed, its size) unless that would exceed the budget.
  void Keep(std::uint64_t stream_seed, std::vector<double> unit);

 private:
  const std::size_t budget_bytes_;
  mutable std::mutex mutex_;
  std::size_t used_bytes_ = 0;
  std::map<std::pair<std::uint64_t, std::size_t>, std::shared_ptr<const std::vector<double>>> records_;
};

}  // namespace allanlab::sim
