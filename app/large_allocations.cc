// Large blocks of the `allanlab` process on transparent huge pages.
//
// `diagnose` writes arrays of the record's length many times over: each model's autocovariance,
// phase variogram and moment sums, and each simulated record of a Monte Carlo view (8 bytes x 1e7
// samples = 80 MB a block). A fresh block is faulted in 4 KiB page by page: on the 1e7-sample
// Gauss-Markov gap record of results/benchmarks/diagnose.md, perf put 18 % of the run's CPU in
// the kernel's page-fault path and 9 % in zeroing fresh blocks. With the blocks on 2 MiB pages
// that record took 49 s instead of 72 s, one model's exact OAVAR moments 1.1-1.4 s instead of
// 2.3 s and its Gaussian views 1.5 s instead of 3.4 s (two threads). Where the kernel's
// transparent huge pages are in madvise mode (Debian's default) a block goes on huge pages only
// when asked, so every block of at least kHugePageAdviceMinBytes is aligned to a huge page and
// advised (a block of that size is fresh memory from the kernel, not yet written). Under
// "always" the advice changes nothing; under "never" it is ignored (common/huge_pages.h).
// Smaller blocks are plain malloc. The values computed do not depend on any of this.
#include <cstdlib>
#include <new>

#include "common/huge_pages.h"

namespace {

using allanlab::kHugePageAdviceMinBytes;
using allanlab::kHugePageBytes;

void* TryAllocate(std::size_t size) {
  if (size < kHugePageAdviceMinBytes) return std::malloc(size == 0 ? 1 : size);
  const std::size_t rounded = (size + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
  void* p = std::aligned_alloc(kHugePageBytes, rounded);
  allanlab::AdviseHugePages(p, rounded);
  return p;
}

void* Allocate(std::size_t size) {
  for (;;) {
    if (void* p = TryAllocate(size)) return p;
    std::new_handler handler = std::get_new_handler();
    if (handler == nullptr) throw std::bad_alloc();
    handler();
  }
}

}  // namespace

// The replaceable forms that allocate by size; the nothrow and sized forms of the standard
// library call these, and the over-aligned forms keep their own pair.
void* operator new(std::size_t size) { return Allocate(size); }
void* operator new[](std::size_t size) { return Allocate(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
