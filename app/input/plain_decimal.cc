#include "app/input/plain_decimal.h"

#include <cstdint>

namespace allanlab::app {

// Digits are read one at a time: a row's numbers are short runs of digits, over which eight
// bytes at a time cost more instructions and measured slower.
const char* ScanPlainDecimal(const char* p, const char* end, double* value, bool* integral) {
  static constexpr double kPowersOfTen[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                            1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                            1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  // At most 19 digits (leading zeros included) fit a uint64 without overflow.
  std::uint64_t digits = 0;
  const char* const first = p;
  for (; p != end && static_cast<unsigned>(*p - '0') < 10; ++p) digits = digits * 10 + (*p - '0');
  std::ptrdiff_t count = p - first;
  if (count == 0) return nullptr;
  int scale = 0;  // the power of ten the digits are multiplied by
  bool plain_integer = true;
  if (p != end && *p == '.') {
    plain_integer = false;
    const char* const fraction = ++p;
    for (; p != end && static_cast<unsigned>(*p - '0') < 10; ++p) digits = digits * 10 + (*p - '0');
    if (p == fraction) return nullptr;
    scale = static_cast<int>(fraction - p);
    count += p - fraction;
  }
  if (count > 19) return nullptr;
  if (p != end && (*p == 'e' || *p == 'E')) {
    plain_integer = false;
    ++p;
    bool negative = false;
    if (p != end && (*p == '+' || *p == '-')) negative = *p++ == '-';
    int exponent = 0;
    const char* start = p;
    for (; p != end && *p >= '0' && *p <= '9' && p - start < 4; ++p) exponent = exponent * 10 + (*p - '0');
    if (p == start) return nullptr;
    scale += negative ? -exponent : exponent;
  }
  if (digits > (std::uint64_t{1} << 53) || scale < -22 || scale > 22) return nullptr;
  const double mantissa = static_cast<double>(digits);
  *value = scale < 0 ? mantissa / kPowersOfTen[-scale] : mantissa * kPowersOfTen[scale];
  *integral = plain_integer;
  return p;
}

}  // namespace allanlab::app
