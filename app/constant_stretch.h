#pragma once
// The longest run of identical consecutive samples of a record: a stuck or saturated sensor, a
// logger repeating its last value, or a quantizer much coarser than the noise. Allan-type
// statistics see zero variance there and the diagnosis would blame some effect for it silently,
// so the commands name it instead.
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

ConstantStretch LongestConstantStretch(std::span<const double> samples);

// A one-line warning when the longest stretch is at least kMinConstantStretch samples and at
// least 0.1 % of the record; nullopt otherwise. sample_rate_hz > 0 converts it to seconds.
inline constexpr std::int64_t kMinConstantStretch = 100;
std::optional<std::string> DescribeConstantStretch(std::span<const double> samples, double sample_rate_hz);

}  // namespace allanlab::app
