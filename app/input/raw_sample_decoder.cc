#include "app/input/raw_sample_decoder.h"

#include <algorithm>
#include <bit>
#include <cstring>

namespace allanlab::app {

RawSampleDecoder::RawSampleDecoder(RawSampleType type, ValueSink sink)
    : type_(type), size_(type == RawSampleType::kFloat32 ? 4 : 8), sink_(std::move(sink)) {}

RawSampleDecoder::RawSampleDecoder(RawSampleType type, BlockSink sink, std::size_t block_values)
    : type_(type), size_(type == RawSampleType::kFloat32 ? 4 : 8), block_sink_(std::move(sink)) {
  block_.resize(block_values < 1 ? 1 : block_values);
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

void RawSampleDecoder::DecodeRun(const unsigned char* p, std::size_t count, double* out) const {
  if constexpr (std::endian::native == std::endian::little) {
    if (type_ == RawSampleType::kFloat64) {
      std::memcpy(out, p, count * sizeof(double));
      return;
    }
    for (std::size_t i = 0; i < count; ++i) {
      float value;
      std::memcpy(&value, p + 4 * i, sizeof value);
      out[i] = static_cast<double>(value);
    }
    return;
  }
  for (std::size_t i = 0; i < count; ++i) out[i] = Decode(p + i * static_cast<std::size_t>(size_));
}

bool RawSampleDecoder::FlushBlock() {
  if (block_count_ == 0) return true;
  const auto first = index_ - static_cast<std::int64_t>(block_count_);
  const bool go_on = block_sink_(std::span<const double>(block_.data(), block_count_), first);
  block_count_ = 0;
  return go_on;
}

bool RawSampleDecoder::Emit(const unsigned char* p) {
  if (!block_sink_) return sink_(Decode(p), index_++);
  block_[block_count_++] = Decode(p);
  ++index_;
  return block_count_ < block_.size() || FlushBlock();
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
  const auto size = static_cast<std::size_t>(size_);
  if (block_sink_) {
    // Whole samples straight into the block, as many at a time as it has room for.
    while (n >= size) {
      const std::size_t take = std::min(n / size, block_.size() - block_count_);
      DecodeRun(p, take, block_.data() + block_count_);
      block_count_ += take;
      index_ += static_cast<std::int64_t>(take);
      p += take * size;
      n -= take * size;
      if (block_count_ == block_.size() && !FlushBlock()) return false;
    }
  }
  while (n >= size) {
    if (!Emit(p)) return false;
    p += size_;
    n -= size;
  }
  std::memcpy(carry_, p, n);
  carried_ = static_cast<int>(n);
  return FlushBlock();
}

bool RawSampleDecoder::FeedStorage(std::span<const double> values) {
  if (!block_sink_ || type_ != RawSampleType::kFloat64 || carried_ != 0 ||
      std::endian::native != std::endian::little) {
    return Feed({reinterpret_cast<const char*>(values.data()), values.size_bytes()});
  }
  if (!FlushBlock()) return false;
  while (!values.empty()) {
    const std::size_t take = std::min(values.size(), block_.size());
    index_ += static_cast<std::int64_t>(take);
    if (!block_sink_(values.first(take), index_ - static_cast<std::int64_t>(take))) return false;
    values = values.subspan(take);
  }
  return true;
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
