#pragma once
// Large arrays backed by 2 MiB pages. A record of 1e8 samples is 800 MB; touched first through
// 4 KiB pages it costs ~200000 page faults, which in our VM took 1.5 s of system time and slowed
// the Allan pass itself through TLB misses (`avar` on 1e8 float64 samples: 3.5 s CPU with 4 KiB
// pages, 1.0 s with 2 MiB pages; results/benchmarks/whole_process.md). Linux only honours the
// request when transparent huge pages are in "madvise" or "always" mode; elsewhere it is a no-op.
#include <cstddef>

namespace allanlab {

// The size of a transparent huge page, and the smallest array AdviseHugePages advises: below
// it at most one huge page would fit, and small blocks are reused from the heap.
inline constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;
inline constexpr std::size_t kHugePageAdviceMinBytes = std::size_t{4} << 20;

// Advises the kernel to back the whole 4 KiB pages of [data, data + bytes) with huge pages.
// Call before the first write to the memory; results never depend on it. Arrays below
// kHugePageAdviceMinBytes are left alone.
void AdviseHugePages(void* data, std::size_t bytes);

// Has the kernel fault in the whole 4 KiB pages of [data, data + bytes) for writing (zeroing the
// fresh ones) without writing to them, so that it may run in one thread while another writes the
// memory: a page already written is left as it is. Why: first-touch page faults of a large
// output array, taken in a thread that would otherwise wait, are not paid by the one that writes
// it. A no-op where the kernel lacks MADV_POPULATE_WRITE (Linux < 5.14): the writer faults the
// pages in as without the call.
void PopulateForWrite(void* data, std::size_t bytes);

}  // namespace allanlab
