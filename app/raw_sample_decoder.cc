#include "app/raw_sample_decoder.h"

#include <bit>
#include <cstring>

namespace allanlab::app {

RawSampleDecoder::RawSampleDecoder(RawSampleType type, ValueSink sink)
    : type_(type), size_(type == RawSampleType::kFloat32 ? 4 : 8), sink_(std::move(sink)) {}

RawSampleDecoder::RawSampleDecoder(RawSampleType type, BlockSink sink, std::size_t block_values)
    : type_(type), size_(type == RawSampleType::kFloat32 ? 4 : 8), block_sink_(std::move(sink)) {
  block_.reserve(block_values < 1 ? 1 : block_values);
}

double RawSampleDecoder::Decode(const unsigned char* p) const {
  double value;
  // Assembled byte by byte from little-endian, so the result does not depend on the host.
  if (type_ == RawSampleType::kFloat32) {
    std::uint32_t bits = 0;
    for (int i = 3; i >= 0; --i) bits = (bits << 8) | p[i];
    value = static_cast<double>(std::bit_cast<float>(bits));
  } else {
    std::uint64_t bits = 0;
    for (int i = 7; i >= 0; --i) bits = (bits << 8) | p[i];
    value = std::bit_cast<double>(bits);
  }
  return value;
}

bool RawSampleDecoder::FlushBlock() {
  if (block_.empty()) return true;
  const auto first = index_ - static_cast<std::int64_t>(block_.size());
  const bool go_on = block_sink_(block_, first);
  block_.clear();
  return go_on;
}

bool RawSampleDecoder::Emit(const unsigned char* p) {
  if (!block_sink_) return sink_(Decode(p), index_++);
  block_.push_back(Decode(p));
  ++index_;
  return block_.size() < block_.capacity() || FlushBlock();
}

bool RawSampleDecoder::Feed(std::span<const char> bytes) {
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data());
  std::size_t n = bytes.size();
  if (carried_ > 0) {
    const std::size_t take = std::min<std::size_t>(n, static_cast<std::size_t>(size_ - carried_));
    std::memcpy(carry_ + carried_, p, take);
    carried_ += static_cast<int>(take);
    p += take;
    n -= take;
    if (carried_ < size_) return true;
    carried_ = 0;
    if (!Emit(carry_)) return false;
  }
  while (n >= static_cast<std::size_t>(size_)) {
    if (!Emit(p)) return false;
    p += size_;
    n -= static_cast<std::size_t>(size_);
  }
  std::memcpy(carry_, p, n);
  carried_ = static_cast<int>(n);
  return FlushBlock();
}

bool RawSampleDecoder::Finish(std::string* why) const {
  if (carried_ == 0) return true;
  if (why) {
    *why = "the data ends " + std::to_string(carried_) + " byte(s) into a " +
           std::to_string(size_) + "-byte sample: truncated file, or not " +
           (type_ == RawSampleType::kFloat32 ? "float32" : "float64") + " data";
  }
  return false;
}

}  // namespace allanlab::app
