#pragma once
// The common shape of a number in a text record, read without the general parser: a plain
// decimal "123.456e-7" whose digits fit 2^53 and whose power of ten is at most 22 in size. The
// value is then one correctly rounded multiplication or division of two exact doubles (Clinger's
// fast path), the same double std::from_chars and strtod return, at a fraction of their cost.
// Anything else (a sign, more digits, a larger exponent, hex, "nan") is left to the general
// parser (app/input/text_record_parser.h, ParseNumberField).
#include <string_view>

namespace allanlab::app {

// Reads the plain decimal that starts at p (digits, then optionally '.' and at least one digit,
// then optionally 'e' or 'E', a sign and one to four digits) and returns the end of what it read,
// with the value in *value and, in *integral, whether it had neither a point nor an exponent.
// Returns nullptr, leaving *value alone, when the text at p is not such a decimal or its value is
// outside the fast path. The caller decides whether the character at the returned end (a
// delimiter, a line end) may end the number.
const char* ScanPlainDecimal(const char* p, const char* end, double* value, bool* integral);

// The whole of `s` as a plain decimal: true with *value set, else false with *value left alone.
inline bool ParsePlainDecimal(std::string_view s, double* value) {
  double v;
  bool integral;
  if (ScanPlainDecimal(s.data(), s.data() + s.size(), &v, &integral) != s.data() + s.size() || s.empty()) {
    return false;
  }
  *value = v;
  return true;
}

}  // namespace allanlab::app
