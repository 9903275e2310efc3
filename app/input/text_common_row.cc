// TextRecordParser::ReadCommonRow: the data row nearly every line of a long record is (plain
// decimals between single delimiters, nothing else on the line that matters), read in one pass
// over its bytes. Any other line (a comment, a blank line, quotes, spaces around a field, a
// missing value, an integer time stamp, an error to report, a line not whole in this chunk) is
// declined and goes to ParseLine, whose rules decide; a row read here is the row ParseLine gives.
#include <algorithm>
#include <utility>

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
  if (common_shape_.field_roles.empty()) {
    int last = time_index_;
    for (int index : value_indices_) last = std::max(last, index);
    common_shape_.delimiter = delimiter_;
    common_shape_.values = values_.size();
    std::vector<int>& roles = common_shape_.field_roles;
    roles.assign(static_cast<std::size_t>(last) + 1, kSkippedField);
    if (time_index_ >= 0) roles[static_cast<std::size_t>(time_index_)] = kTimeField;
    for (std::size_t k = 0; k < value_indices_.size(); ++k) {
      roles[static_cast<std::size_t>(value_indices_[k])] = static_cast<int>(k);
    }
  }
  return true;
}

// Inlined into its two callers below, which read rows in a loop: a call per row measured 5 % more
// instructions for the whole read.
[[gnu::always_inline]] inline const char* TextRecordParser::ScanCommonRow(
    const CommonRowShape& shape, const char* p, const char* const end, double* values,
    double* time) {
  const char* const start = p;
  const char delimiter = shape.delimiter;
  const std::size_t fields = shape.field_roles.size();
  for (std::size_t field = 0; field < fields; ++field) {
    if (field > 0) {
      if (p == end || *p != delimiter) return nullptr;
      ++p;
    }
    const int role = shape.field_roles[field];
    if (role == kSkippedField) {
      // Not read, but a NUL byte or a comment anywhere on the line is ParseLine's to handle.
      for (; p != end && *p != delimiter; ++p) {
        if (*p == '\n' || *p == '\0' || *p == '#') return nullptr;
      }
      continue;
    }
    // ParseNumberField's first try: a sign, then a plain decimal filling the field.
    const bool minus = p != end && *p == '-';
    if (p != end && (minus || *p == '+')) ++p;
    double v;
    bool integral;
    const char* const number_end = ScanPlainDecimal(p, end, &v, &integral);
    if (number_end == nullptr || number_end == end) return nullptr;
    p = number_end;
    if (*p != delimiter && *p != '\n' && *p != '\r') return nullptr;
    if (minus) v = -v;
    if (role == kTimeField) {
      // An integer time stamp sets the origin of the times after it: ParseTimeField's to do.
      if (integral) return nullptr;
      *time = v;
    } else {
      values[role] = v;
    }
  }
  // The line's end: right after the last field read ('\r' is a blank before it), or after
  // fields that are not read.
  if (p == end) return nullptr;
  if (*p == '\r') {
    if (p + 1 == end || p[1] != '\n') return nullptr;
    ++p;
  } else if (*p == delimiter) {
    for (; p != end && *p != '\n'; ++p) {
      if (*p == '\0' || *p == '#') return nullptr;
    }
    if (p == end) return nullptr;
  }
  if (*p != '\n') return nullptr;
  ++p;
  if (static_cast<std::size_t>(p - start) > kMaxLineBytes) return nullptr;  // ParseLine's message
  return p;
}

[[gnu::always_inline]] inline bool TextRecordParser::PassCommonRow(std::span<const double> values,
                                                                   double time) {
  ++line_;
  TextRow row;
  row.line = line_;
  row.value = values.front();
  row.values = values;
  if (time_index_ >= 0) {
    row.has_time = true;
    row.time = time;
  }
  ++data_rows_;
  if (sink_(row)) return true;
  failed_ = true;
  return false;
}

std::size_t TextRecordParser::ReadCommonRow(std::string_view chunk) {
  double time = 0.0;
  const char* const next = ScanCommonRow(common_shape_, chunk.data(), chunk.data() + chunk.size(),
                                         values_.data(), &time);
  if (next == nullptr) return 0;
  PassCommonRow(values_, time);
  return static_cast<std::size_t>(next - chunk.data());
}

void TextRecordParser::ReadCommonRows(const CommonRowShape& shape, std::string_view text,
                                      CommonRows* rows) {
  const std::size_t width = shape.values;
  const char* p = text.data();
  const char* const end = p + text.size();
  std::size_t n = 0;
  while (p != end) {
    if ((n + 1) * width > rows->values.size()) {
      // Grown, never shrunk: the storage of one chunk serves the next.
      rows->values.resize(std::max<std::size_t>(2 * rows->values.size(), std::size_t{1} << 14) +
                          width);
      rows->times.resize(rows->values.size() / width);
    }
    const char* const next =
        ScanCommonRow(shape, p, end, rows->values.data() + n * width, rows->times.data() + n);
    if (next == nullptr) break;
    p = next;
    ++n;
  }
  rows->rows = n;
  rows->bytes = static_cast<std::size_t>(p - text.data());
}

std::size_t TextRecordParser::ReadCommonRun(std::string_view chunk) {
  ReadCommonRows(common_shape_, chunk, &run_rows_);
  PassCommonRows(run_rows_);
  return run_rows_.bytes;
}

void TextRecordParser::PassRunsAsBlocks(RowBlockSink sink) { block_sink_ = std::move(sink); }

bool TextRecordParser::PassCommonRows(const CommonRows& rows) {
  const std::size_t width = common_shape_.values;
  if (block_sink_ && rows.rows > 0) {
    TextRowBlock block;
    block.first_line = line_ + 1;
    block.rows = rows.rows;
    block.width = width;
    block.values = {rows.values.data(), rows.rows * width};
    block.has_time = time_index_ >= 0;
    if (block.has_time) block.times = {rows.times.data(), rows.rows};
    line_ += static_cast<std::int64_t>(rows.rows);
    data_rows_ += static_cast<std::int64_t>(rows.rows);
    if (block_sink_(block)) return true;
    failed_ = true;
    return false;
  }
  for (std::size_t i = 0; i < rows.rows; ++i) {
    if (!PassCommonRow({rows.values.data() + i * width, width}, rows.times[i])) return false;
  }
  return true;
}

}  // namespace allanlab::app
