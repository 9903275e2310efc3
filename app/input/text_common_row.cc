// TextRecordParser::ReadCommonRow: the data row nearly every line of a long record is (plain
// decimals between single delimiters, nothing else on the line that matters), read in one pass
// over its bytes. Any other line (a comment, a blank line, quotes, spaces around a field, a
// missing value, an integer time stamp, an error to report, a line not whole in this chunk) is
// declined and goes to ParseLine, whose rules decide; a row read here is the row ParseLine gives.
#include <algorithm>

#include "app/input/plain_decimal.h"
#include "app/input/text_record_parser.h"

namespace allanlab::app {

bool TextRecordParser::CommonRowsPossible() {
  // Whitespace columns, held probe rows and integer stamps (relative to their origin) keep to
  // ParseLine; so does anything before the columns are chosen.
  if (!format_known_ || probing_ || delimiter_ == ' ' || values_.empty() ||
      (time_index_ >= 0 && time_origin_set_)) {
    return false;
  }
  if (field_roles_.empty()) {
    int last = time_index_;
    for (int index : value_indices_) last = std::max(last, index);
    field_roles_.assign(static_cast<std::size_t>(last) + 1, kSkippedField);
    if (time_index_ >= 0) field_roles_[static_cast<std::size_t>(time_index_)] = kTimeField;
    for (std::size_t k = 0; k < value_indices_.size(); ++k) {
      field_roles_[static_cast<std::size_t>(value_indices_[k])] = static_cast<int>(k);
    }
  }
  return true;
}

std::size_t TextRecordParser::ReadCommonRow(std::string_view chunk) {
  const char* p = chunk.data();
  const char* const end = p + chunk.size();
  double time = 0.0;
  const std::size_t fields = field_roles_.size();
  for (std::size_t field = 0; field < fields; ++field) {
    if (field > 0) {
      if (p == end || *p != delimiter_) return 0;
      ++p;
    }
    const int role = field_roles_[field];
    if (role == kSkippedField) {
      // Not read, but a NUL byte or a comment anywhere on the line is ParseLine's to handle.
      for (; p != end && *p != delimiter_; ++p) {
        if (*p == '\n' || *p == '\0' || *p == '#') return 0;
      }
      continue;
    }
    // ParseNumberField's first try: a sign, then a plain decimal filling the field.
    const bool minus = p != end && *p == '-';
    if (p != end && (minus || *p == '+')) ++p;
    double v;
    bool integral;
    const char* const number_end = ScanPlainDecimal(p, end, &v, &integral);
    if (number_end == nullptr || number_end == end) return 0;
    p = number_end;
    if (*p != delimiter_ && *p != '\n' && *p != '\r') return 0;
    if (minus) v = -v;
    if (role == kTimeField) {
      // An integer time stamp sets the origin of the times after it: ParseTimeField's to do.
      if (integral) return 0;
      time = v;
    } else {
      values_[static_cast<std::size_t>(role)] = v;
    }
  }
  // The line's end: right after the last field read ('\r' is a blank before it), or after
  // fields that are not read.
  if (p == end) return 0;
  if (*p == '\r') {
    if (p + 1 == end || p[1] != '\n') return 0;
    ++p;
  } else if (*p == delimiter_) {
    for (; p != end && *p != '\n'; ++p) {
      if (*p == '\0' || *p == '#') return 0;
    }
    if (p == end) return 0;
  }
  if (*p != '\n') return 0;
  const auto used = static_cast<std::size_t>(p + 1 - chunk.data());
  if (used > kMaxLineBytes) return 0;  // ParseLine's message
  ++line_;
  TextRow row;
  row.line = line_;
  row.value = values_.front();
  row.values = values_;
  if (time_index_ >= 0) {
    row.has_time = true;
    row.time = time;
  }
  ++data_rows_;
  if (!sink_(row)) failed_ = true;
  return used;
}

}  // namespace allanlab::app
