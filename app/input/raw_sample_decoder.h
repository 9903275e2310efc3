#pragma once
// Raw little-endian float32 or float64 samples, no header, decoded from byte chunks of any size
// (a value split across two chunks is carried over).
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace allanlab::app {

enum class RawSampleType { kFloat32, kFloat64 };

class RawSampleDecoder {
 public:
  // Called with each value and its 0-based index; returning false stops the decoding.
  using ValueSink = std::function<bool(double value, std::int64_t index)>;

  RawSampleDecoder(RawSampleType type, ValueSink sink);
  // Values in blocks of up to `block_values` (the index of the first one), which spares a call
  // per value on records of 1e8 samples. Blocks end where a Feed ends.
  using BlockSink = std::function<bool(std::span<const double> values, std::int64_t first_index)>;
  RawSampleDecoder(RawSampleType type, BlockSink sink, std::size_t block_values);
  // Returns false when the sink stopped.
  bool Feed(std::span<const char> bytes);
  // The same for bytes that are the storage of `values` (so read as doubles without a copy): in
  // block mode, for float64 on a little-endian host with no partial sample carried over, the
  // values go to the sink as they lie; otherwise as Feed(their bytes).
  bool FeedStorage(std::span<const double> values);
  // Fails when the byte count is not a multiple of the sample size (a truncated file).
  bool Finish(std::string* why) const;
  std::int64_t values() const { return index_; }
  int sample_bytes() const { return size_; }

 private:
  bool Emit(const unsigned char* p);
  double Decode(const unsigned char* p) const;
  // `count` whole samples from p into out: a copy on a little-endian host, else byte by byte.
  void DecodeRun(const unsigned char* p, std::size_t count, double* out) const;
  bool FlushBlock();

  RawSampleType type_;
  int size_;
  ValueSink sink_;
  BlockSink block_sink_;
  std::vector<double> block_;  // block mode: its first block_count_ values decoded, not yet passed on
  std::size_t block_count_ = 0;
  unsigned char carry_[8] = {};
  int carried_ = 0;
  std::int64_t index_ = 0;
};

}  // namespace allanlab::app
