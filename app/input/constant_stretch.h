#pragma once
// The longest run of identical consecutive samples of a record: a stuck or saturated sensor, a
// logger repeating its last value, or a quantizer much coarser than the noise. Allan-type
// statistics see zero variance there and the diagnosis would blame some effect for it silently,
// so the record reader tracks it (app/input/record_reader.h) and the commands name it.
#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace allanlab::app {

struct ConstantStretch {
  std::int64_t first = 0;   // 0-based index of its first sample
  std::int64_t length = 0;  // samples
  double value = 0.0;       // in the record's own units
};

// True when two consecutive values compare equal (one vectorised pass).
bool AnyEqualNeighbours(std::span<const double> values);

// Streaming: one comparison per sample.
class ConstantStretchTracker {
 public:
  void Add(double value) {
    if (count_ > 0 && value == current_.value) {
      ++current_.length;
    } else {
      current_ = {count_, 1, value};
    }
    ++count_;
    if (current_.length > longest_.length) longest_ = current_;
  }
  // The same as Add for each value: the whole block at once when it holds no two equal
  // neighbours (the common case, one vectorised pass), else 64 at a time.
  void AddBlock(std::span<const double> values) {
    if (!values.empty() && count_ > 0 && values.front() != current_.value &&
        !AnyEqualNeighbours(values)) {
      // Every run among these values has length 1, none longer than the longest so far (>= 1).
      count_ += static_cast<std::int64_t>(values.size());
      current_ = {count_ - 1, 1, values.back()};
      return;
    }
    constexpr std::size_t kLanes = 64;
    std::size_t i = 0;
    for (; i + kLanes <= values.size(); i += kLanes) {
      bool repeat = count_ == 0 || longest_.length == 0 || values[i] == current_.value;
      for (std::size_t k = i + 1; k < i + kLanes; ++k) repeat |= values[k] == values[k - 1];
      if (repeat) {
        for (std::size_t k = i; k < i + kLanes; ++k) Add(values[k]);
        continue;
      }
      count_ += static_cast<std::int64_t>(kLanes);
      current_ = {count_ - 1, 1, values[i + kLanes - 1]};
    }
    for (; i < values.size(); ++i) Add(values[i]);
  }
  const ConstantStretch& longest() const { return longest_; }

 private:
  std::int64_t count_ = 0;
  ConstantStretch current_, longest_;
};

ConstantStretch LongestConstantStretch(std::span<const double> samples);

// A one-line description when the stretch is at least kMinConstantStretch samples and at least
// 0.1 % of the record's `samples`; nullopt otherwise. sample_rate_hz > 0 converts it to seconds.
inline constexpr std::int64_t kMinConstantStretch = 100;
std::optional<std::string> DescribeConstantStretch(const ConstantStretch& stretch, std::int64_t samples,
                                                   double sample_rate_hz);

}  // namespace allanlab::app
