#include "common/all_finite.h"

#include <bit>
#include <cstdint>

namespace allanlab {

// An exponent field of all ones (infinity or NaN) plus one carries into the sign bit; every
// finite exponent stays below it. Integer and/add/or, which vectorise in SSE2 and AVX2.
__attribute__((target_clones("avx2", "default"))) bool AllFinite(std::span<const double> values) {
  constexpr std::uint64_t kExponent = 0x7ff0000000000000ULL, kExponentOne = 0x0010000000000000ULL;
  std::uint64_t carry = 0;
  for (double v : values) carry |= (std::bit_cast<std::uint64_t>(v) & kExponent) + kExponentOne;
  return (carry >> 63) == 0;
}

}  // namespace allanlab
