#include "app/input/heap_tuning.h"

#include <malloc.h>

namespace allanlab::app {

void KeepFreedMemoryInHeap() {
#if defined(__GLIBC__)
  // Every request from the heap, none by mmap (M_MMAP_THRESHOLD cannot exceed 32 MiB, and the
  // tables are larger), and no trimming of the heap's top below 1 GiB of free space, so blocks
  // freed by one fit serve the next.
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
}

}  // namespace allanlab::app
