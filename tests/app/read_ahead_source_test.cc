// The read-ahead byte source: the wrapped source's bytes in order, whatever the sizes of the
// reads on either side, and its error after every byte before it, once.
#include "app/input/read_ahead_source.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace allanlab::app {
namespace {

char ByteAt(std::size_t i) { return static_cast<char>((i * 2654435761u) >> 13); }

// `total` pattern bytes in reads of varying size (at most `step`), then the end, or, with `fail`,
// an error instead of the end.
class PatternSource : public ByteSource {
 public:
  PatternSource(std::size_t total, std::size_t step, bool fail) : total_(total), step_(step), fail_(fail) {}
  bool Read(std::span<char> out, std::size_t* got, std::string* why) override {
    *got = 0;
    if (position_ == total_) {
      if (fail_) *why = "pattern: truncated xz data";
      return !fail_;
    }
    const std::size_t n = std::min({out.size(), total_ - position_, 1 + (calls_++ * 7919) % step_});
    for (std::size_t k = 0; k < n; ++k) out[k] = ByteAt(position_ + k);
    position_ += n;
    *got = n;
    return true;
  }
  Compression compression() const override { return Compression::kXz; }

 private:
  std::size_t total_, step_;
  bool fail_;
  std::size_t position_ = 0, calls_ = 0;
};

struct Drained {
  std::vector<char> bytes;
  bool ok = true;
  std::string why;
};

Drained Drain(ByteSource* source, std::size_t read_size) {
  Drained d;
  std::vector<char> buffer(read_size);
  while (true) {
    std::size_t got = 0;
    if (!source->Read(buffer, &got, &d.why)) {
      d.ok = false;
      return d;
    }
    if (got == 0) return d;
    d.bytes.insert(d.bytes.end(), buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(got));
  }
}

TEST(ReadAheadSourceTest, GivesTheSameBytesForAnyReadSizes) {
  const std::size_t total = 3 * kReadAheadBufferBytes * kReadAheadBuffers + 12345;
  for (const std::size_t producer_step : {std::size_t{1000}, kReadAheadBufferBytes, 3 * kReadAheadBufferBytes}) {
    for (const std::size_t read_size : {std::size_t{1}, std::size_t{4096}, kReadAheadBufferBytes + 17}) {
      if (read_size == 1 && producer_step != 1000) continue;  // a byte at a time: once is enough
      const std::size_t bytes = read_size == 1 ? 100000 : total;
      auto source = ReadAhead(std::make_unique<PatternSource>(bytes, producer_step, false));
      EXPECT_EQ(source->compression(), Compression::kXz);
      const Drained d = Drain(source.get(), read_size);
      ASSERT_TRUE(d.ok) << d.why;
      ASSERT_EQ(d.bytes.size(), bytes);
      for (std::size_t i = 0; i < bytes; ++i) {
        ASSERT_EQ(d.bytes[i], ByteAt(i)) << "byte " << i << ", reads of " << read_size;
      }
      std::size_t got = 1;
      std::vector<char> more(16);
      EXPECT_TRUE(source->Read(more, &got, nullptr));  // the end stays the end
      EXPECT_EQ(got, 0u);
    }
  }
}

TEST(ReadAheadSourceTest, AnErrorComesAfterEveryByteBeforeIt) {
  const std::size_t total = 2 * kReadAheadBufferBytes * kReadAheadBuffers + 999;
  auto source = ReadAhead(std::make_unique<PatternSource>(total, kReadAheadBufferBytes, true));
  const Drained d = Drain(source.get(), 65536);
  EXPECT_FALSE(d.ok);
  EXPECT_EQ(d.why, "pattern: truncated xz data");
  ASSERT_EQ(d.bytes.size(), total);
  for (std::size_t i = 0; i < total; ++i) ASSERT_EQ(d.bytes[i], ByteAt(i)) << i;
}

TEST(ReadAheadSourceTest, StopsWhenDroppedBeforeTheEnd) {
  // The caller gives up after one read (a parse error): the thread stops with the source.
  auto source = ReadAhead(std::make_unique<PatternSource>(std::size_t{1} << 26, 4096, false));
  std::vector<char> buffer(100);
  std::size_t got = 0;
  ASSERT_TRUE(source->Read(buffer, &got, nullptr));
  EXPECT_EQ(buffer[0], ByteAt(0));
  source.reset();
}

}  // namespace
}  // namespace allanlab::app
