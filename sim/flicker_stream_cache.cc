#include "sim/flicker_stream_cache.h"

namespace allanlab::sim {

std::shared_ptr<const std::vector<double>> FlickerStreamCache::Find(std::uint64_t stream_seed, std::size_t n) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  const auto it = records_.find({stream_seed, n});
  return it == records_.end() ? nullptr : it->second;
}

void FlickerStreamCache::Keep(std::uint64_t stream_seed, std::vector<double> unit) {
  const std::size_t bytes = unit.size() * sizeof(double);
  const std::lock_guard<std::mutex> lock(mutex_);
  if (used_bytes_ + bytes > budget_bytes_ || records_.contains({stream_seed, unit.size()})) return;
  used_bytes_ += bytes;
  const std::size_t n = unit.size();
  records_.emplace(std::make_pair(stream_seed, n), std::make_shared<const std::vector<double>>(std::move(unit)));
}

}  // namespace allanlab::sim
