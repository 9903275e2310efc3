#include "app/input/constant_stretch.h"

#include "app/reports/provenance.h"
#include "common/number_text.h"

namespace allanlab::app {

// Counted rather than or-ed: GCC vectorises the sum of comparison results (4 neighbours per
// instruction pair in AVX2), not a boolean reduction.
__attribute__((target_clones("avx2", "default"))) bool AnyEqualNeighbours(std::span<const double> values) {
  std::int64_t equal = 0;
  for (std::size_t k = 1; k < values.size(); ++k) equal += values[k] == values[k - 1];
  return equal != 0;
}

ConstantStretch LongestConstantStretch(std::span<const double> samples) {
  ConstantStretchTracker tracker;
  tracker.AddBlock(samples);
  return tracker.longest();
}

std::optional<std::string> DescribeConstantStretch(const ConstantStretch& s, std::int64_t samples,
                                                   double sample_rate_hz) {
  if (s.length < kMinConstantStretch || 1000 * s.length < samples) return std::nullopt;
  return std::to_string(s.length) + " identical samples in a row (" +
         ShortestDecimal(static_cast<double>(s.length) / sample_rate_hz) + " s from sample " +
         std::to_string(s.first) + ", value " + ShortestDecimal(s.value) +
         "): a stuck or saturated sensor, a repeated logger value, or a quantizer coarser than the "
         "noise; the Allan variance sees no noise there";
}

}  // namespace allanlab::app
