#pragma once
// Numbers as text, the two ways the tool prints them: round-trip exact (provenance, machine
// readable outputs, values echoed in messages) and to a number of significant digits (tables and
// reports for people).
#include <string>

namespace allanlab {

// The shortest text that reads back as exactly `value` (std::to_chars): 0.1, 1e+300, 3.0000000000000004.
std::string ShortestDecimal(double value);

// "%.*g" with `digits` significant digits; "nan", "inf" and "-inf" spelt out.
std::string SignificantDigits(double value, int digits);

}  // namespace allanlab
