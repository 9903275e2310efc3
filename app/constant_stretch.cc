#include "app/constant_stretch.h"

#include "app/provenance.h"

namespace allanlab::app {

ConstantStretch LongestConstantStretch(std::span<const double> samples) {
  ConstantStretch best;
  std::int64_t start = 0;
  const auto n = static_cast<std::int64_t>(samples.size());
  for (std::int64_t k = 1; k <= n; ++k) {
    if (k < n && samples[k] == samples[start]) continue;
    if (k - start > best.length) best = {start, k - start, samples[start]};
    start = k;
  }
  return best;
}

std::optional<std::string> DescribeConstantStretch(std::span<const double> samples, double sample_rate_hz) {
  const ConstantStretch s = LongestConstantStretch(samples);
  if (s.length < kMinConstantStretch || 1000 * s.length < static_cast<std::int64_t>(samples.size())) {
    return std::nullopt;
  }
  return std::to_string(s.length) + " identical samples in a row (" +
         ShortestDecimal(static_cast<double>(s.length) / sample_rate_hz) + " s from sample " +
         std::to_string(s.first) + ", value " + ShortestDecimal(s.value) +
         "): a stuck or saturated sensor, a repeated logger value, or a quantizer coarser than the "
         "noise; the Allan variance sees no noise there";
}

}  // namespace allanlab::app
