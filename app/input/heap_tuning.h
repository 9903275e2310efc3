#pragma once

namespace allanlab::app {

// Keeps freed blocks of any size in the heap instead of returning them to the kernel.
// Why: the fits rebuild multi-megabyte tables (covariance model, flicker kernels) thousands of
// times; with glibc's defaults every such block is a fresh mmap whose pages are zero-filled on
// first touch, and `diagnose` on a published curve spent 13 s of 31 s CPU in the kernel doing
// that (0.07 s once blocks are reused). Results do not change. Call once, first thing in main().
void KeepFreedMemoryInHeap();

}  // namespace allanlab::app
