#pragma once
// A per-thread memo of a pure function's values: the value kept for `key` in `memo`, computed by
// `compute()` the first time. Why per thread: the fits that call these functions run on two
// threads, and a shared map's lock was contended. The memo is emptied when it reaches
// `max_entries`, so a long run's memory stays bounded; a value computed again is the same bits.
//
// Use with a map declared `thread_local` at the call site (std::map or std::unordered_map).
#include <cstddef>

namespace allanlab {

template <class Map, class Compute>
const typename Map::mapped_type& ThreadMemo(Map& memo, std::size_t max_entries, const typename Map::key_type& key,
                                            Compute&& compute) {
  if (const auto it = memo.find(key); it != memo.end()) return it->second;
  if (memo.size() >= max_entries) memo.clear();
  return memo.emplace(key, compute()).first->second;
}

}  // namespace allanlab
