#pragma once
// A byte source read a few buffers ahead in a second thread: the decoder of an xz or gzip file
// fills the next buffers while the caller parses the last one, so that reading a compressed
// record takes about as long as decompressing it alone (whichever of the two is slower sets the
// pace, not their sum).
//
// The bytes, their order and every error are those of the wrapped source: a read error or
// corrupt or truncated data is returned by the Read that reaches it, after every byte before it,
// with the wrapped source's message. So what the caller computes does not depend on whether the
// thread runs ahead or not.
#include <cstddef>
#include <memory>

#include "app/input/byte_source.h"

namespace allanlab::app {

// Buffers of kReadAheadBufferBytes, at most kReadAheadBuffers filled ahead of the caller.
inline constexpr std::size_t kReadAheadBufferBytes = std::size_t{1} << 18;
inline constexpr int kReadAheadBuffers = 4;

// Takes `source` over and starts its reading thread; the thread stops when the returned source
// is destroyed (after the Read it is in, if any).
std::unique_ptr<ByteSource> ReadAhead(std::unique_ptr<ByteSource> source);

}  // namespace allanlab::app
