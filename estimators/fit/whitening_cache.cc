#include "estimators/fit/whitening_cache.h"

#include <cstring>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

namespace allanlab::estimators {
namespace {

struct Entry {
  Eigen::VectorXd x;
  bool ok = false;
  Eigen::MatrixXd w;
};

struct Cache {
  WhiteningFunction whitening;
  std::size_t capacity = 0;
  std::mutex mutex;
  std::vector<Entry> entries;  // a ring: `next` is overwritten first once full
  std::size_t next = 0;
};

// Bitwise: a key equal in value but not in bits (0.0 and -0.0) is only a miss.
bool SameBits(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() &&
         std::memcmp(a.data(), b.data(), static_cast<std::size_t>(a.size()) * sizeof(double)) == 0;
}

}  // namespace

WhiteningFunction CachedWhitening(WhiteningFunction whitening, std::size_t capacity) {
  auto cache = std::make_shared<Cache>();
  cache->whitening = std::move(whitening);
  cache->capacity = capacity > 0 ? capacity : 1;
  return [cache](const Eigen::VectorXd& x, Eigen::MatrixXd* w) {
    {
      const std::lock_guard<std::mutex> lock(cache->mutex);
      for (const Entry& e : cache->entries) {
        if (!SameBits(e.x, x)) continue;
        if (e.ok) *w = e.w;
        return e.ok;
      }
    }
    // Formed outside the lock: another thread may form the same x meanwhile, with the same bits.
    Entry e;
    e.x = x;
    e.ok = cache->whitening(x, &e.w);
    if (e.ok) *w = e.w;
    const bool ok = e.ok;
    const std::lock_guard<std::mutex> lock(cache->mutex);
    if (cache->entries.size() < cache->capacity) {
      cache->entries.push_back(std::move(e));
    } else {
      cache->entries[cache->next] = std::move(e);
      cache->next = (cache->next + 1) % cache->capacity;
    }
    return ok;
  };
}

}  // namespace allanlab::estimators
