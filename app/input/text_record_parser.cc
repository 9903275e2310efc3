#include "app/input/text_record_parser.h"

#include "app/input/plain_decimal.h"
#include "common/piece_sharing.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <system_error>
#include <utility>

namespace allanlab::app {
namespace {

bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

std::string_view Trim(std::string_view s) {
  while (!s.empty() && IsBlank(s.front())) s.remove_prefix(1);
  while (!s.empty() && IsBlank(s.back())) s.remove_suffix(1);
  return s;
}

char Lower(char c) { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c; }

bool EqualsIgnoreCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (Lower(a[i]) != Lower(b[i])) return false;
  }
  return true;
}

bool AllDigits(std::string_view s) {
  if (s.empty()) return false;
  for (char c : s) {
    if (c < '0' || c > '9') return false;
  }
  return true;
}

// Messages quote user text; keep them one line and short even for binary garbage.
std::string Shown(std::string_view text) {
  std::string out;
  for (char c : text.substr(0, 40)) {
    out +=
        (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) ? '?' : c;
  }
  if (text.size() > 40) out += "...";
  return out;
}

bool IsMissingMarker(std::string_view s) {
  return s.empty() || EqualsIgnoreCase(s, "na") || EqualsIgnoreCase(s, "n/a");
}

}  // namespace

bool ParseNumberField(std::string_view field, double* value) {
  // Nearly every field is a bare signed decimal: try that before trimming, quotes and markers.
  if (!field.empty()) {
    std::string_view bare = field;
    const bool minus = bare.front() == '-';
    if (minus || bare.front() == '+') bare.remove_prefix(1);
    if (ParsePlainDecimal(bare, value)) {
      if (minus) *value = -*value;
      return true;
    }
  }
  std::string_view s = Trim(field);
  if (s.size() >= 2 && s.front() == '"' && s.back() == '"') s = Trim(s.substr(1, s.size() - 2));
  if (IsMissingMarker(s)) {
    *value = std::numeric_limits<double>::quiet_NaN();
    return true;
  }
  bool negative = false;
  if (s.front() == '+' || s.front() == '-') {
    negative = s.front() == '-';
    s.remove_prefix(1);
    // "+-1" and "--1" are not numbers.
    if (s.empty() || s.front() == '+' || s.front() == '-') return false;
  }
  if (ParsePlainDecimal(s, value)) {
    if (negative) *value = -*value;
    return true;
  }
  std::chars_format format = std::chars_format::general;
  if (s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X')) {
    format = std::chars_format::hex;
    s.remove_prefix(2);
  }
  double v = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v, format);
  if (end != s.data() + s.size()) return false;
  if (ec == std::errc::result_out_of_range) {
    // from_chars leaves the value alone on overflow and underflow; strtod knows which it was.
    const std::string text = (format == std::chars_format::hex ? "0x" : "") + std::string(s);
    v = std::strtod(text.c_str(), nullptr);
  } else if (ec != std::errc()) {
    return false;
  }
  *value = negative ? -v : v;
  return true;
}

TextRecordParser::TextRecordParser(std::string column, RowSink sink)
    : column_spec_(column), column_specs_{std::move(column)}, sink_(std::move(sink)) {}

TextRecordParser::TextRecordParser(std::vector<std::string> columns, ColumnChooser choose, RowSink sink)
    : column_specs_(std::move(columns)), choose_(std::move(choose)), sink_(std::move(sink)) {
  if (!column_specs_.empty()) column_spec_ = column_specs_.front();
}

TextRecordParser::~TextRecordParser() = default;

bool TextRecordParser::Fail(std::string message) {
  failed_ = true;
  error_ = std::move(message);
  return false;
}

bool TextRecordParser::Feed(std::string_view chunk) {
  return FeedLines(chunk, two_thread_min_bytes_ > 0);
}

bool TextRecordParser::FeedLines(std::string_view chunk, bool two_threads) {
  if (failed_) return false;
  // Checked again after every line ParseLine reads: it may choose the columns or set the
  // integer time origin.
  bool common_rows = CommonRowsPossible();
  while (!chunk.empty()) {
    if (common_rows && pending_.empty()) {
      if (two_threads && chunk.size() >= two_thread_min_bytes_) {
        const std::size_t used = ReadChunkInTwoThreads(chunk);
        if (failed_) return false;
        if (used > 0) {
          chunk.remove_prefix(used);
          common_rows = CommonRowsPossible();
          continue;
        }
        two_threads = false;  // no line start to cut this chunk at
      }
      if (const std::size_t used = block_sink_ ? ReadCommonRun(chunk) : ReadCommonRow(chunk);
          used > 0) {
        if (failed_) return false;
        chunk.remove_prefix(used);
        continue;
      }
    }
    const std::size_t newline = chunk.find('\n');
    if (newline == std::string_view::npos) {
      if (pending_.size() + chunk.size() > kMaxLineBytes) {
        return Fail("line " + std::to_string(line_ + 1) + " is longer than 1 MiB: not a text " +
                    "record (raw samples? use --format f32|f64)");
      }
      pending_.append(chunk);
      return true;
    }
    std::string_view line = chunk.substr(0, newline);
    chunk.remove_prefix(newline + 1);
    bool ok;
    if (pending_.empty()) {
      if (line.size() > kMaxLineBytes) {
        return Fail("line " + std::to_string(line_ + 1) + " is longer than 1 MiB: not a text " +
                    "record (raw samples? use --format f32|f64)");
      }
      ok = ParseLine(line);
    } else {
      if (pending_.size() + line.size() > kMaxLineBytes) {
        return Fail("line " + std::to_string(line_ + 1) + " is longer than 1 MiB: not a text " +
                    "record (raw samples? use --format f32|f64)");
      }
      pending_.append(line);
      ok = ParseLine(pending_);
      pending_.clear();
    }
    if (!ok) {
      failed_ = true;
      return false;
    }
    common_rows = CommonRowsPossible();
  }
  return true;
}

bool TextRecordParser::Finish() {
  if (failed_) return false;
  if (finished_) return true;
  finished_ = true;
  if (!pending_.empty()) {
    const std::string last = std::move(pending_);
    pending_.clear();
    if (!ParseLine(last)) {
      failed_ = true;
      return false;
    }
  }
  if (probing_ && !DecideHeaderlessTime()) {
    failed_ = true;
    return false;
  }
  return true;
}

void TextRecordParser::Split(std::string_view line, std::vector<std::string_view>* fields) const {
  fields->clear();
  if (delimiter_ == ' ') {
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && IsBlank(line[i])) ++i;
      if (i == line.size()) break;
      const std::size_t start = i;
      while (i < line.size() && !IsBlank(line[i])) ++i;
      fields->push_back(line.substr(start, i - start));
    }
    return;
  }
  std::size_t start = 0;
  while (true) {
    const std::size_t end = line.find(delimiter_, start);
    fields->push_back(Trim(line.substr(start, end == std::string_view::npos ? end : end - start)));
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
}

bool TextRecordParser::ParseTimeField(std::string_view field, double* time) {
  std::string_view s = Trim(field);
  if (s.size() >= 2 && s.front() == '"' && s.back() == '"') s = Trim(s.substr(1, s.size() - 2));
  std::int64_t stamp = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), stamp);
  const bool integer = !s.empty() && ec == std::errc() && end == s.data() + s.size();
  if (!time_origin_set_ && integer) {
    time_origin_set_ = true;
    time_origin_ = stamp;
  }
  std::int64_t since_origin = 0;
  if (integer && time_origin_set_ && !__builtin_sub_overflow(stamp, time_origin_, &since_origin)) {
    *time = static_cast<double>(since_origin);
    return true;
  }
  if (!ParseNumberField(field, time)) return false;
  if (time_origin_set_) *time -= static_cast<double>(time_origin_);
  return true;
}

bool TextRecordParser::ChooseColumns(const std::vector<std::string_view>& first, bool header) {
  has_header_ = header;
  std::vector<std::string> names;
  for (std::string_view f : first) {
    if (f.size() >= 2 && f.front() == '"' && f.back() == '"') f = Trim(f.substr(1, f.size() - 2));
    names.emplace_back(header ? std::string(f) : "");
  }
  if (header) {
    for (std::size_t i = 0; i < names.size() && time_index_ < 0; ++i) {
      for (const TimeColumnName& t : kTimeColumnNames) {
        if (EqualsIgnoreCase(names[i], t.name)) {
          time_index_ = static_cast<int>(i);
          time_column_ = names[i];
          time_name_ = &t;
          break;
        }
      }
    }
  }
  if (column_specs_.empty() && choose_) {
    std::string why;
    if (!choose_(names, time_index_, &column_specs_, &why)) {
      error_is_usage_ = true;
      return Fail(why);
    }
    column_spec_ = column_specs_.empty() ? std::string() : column_specs_.front();
  }
  if (column_specs_.empty()) column_specs_.emplace_back();
  for (const std::string& spec : column_specs_) {
    int index = -1;
    if (!ResolveColumn(spec, names, header, &index)) return false;
    for (std::size_t k = 0; k < value_indices_.size(); ++k) {
      if (value_indices_[k] == index) {
        error_is_usage_ = true;
        return Fail("--columns: " + Shown(spec) + " names column " + std::to_string(index) +
                    " twice (as " + Shown(column_specs_[k]) + ")");
      }
    }
    value_indices_.push_back(index);
  }
  value_index_ = value_indices_.front();
  error_is_usage_ = false;
  for (int index : value_indices_) {
    value_columns_.push_back(header ? names[index] : "column " + std::to_string(index));
    // The time column chosen as (one of) the data: it then carries no time information.
    if (index == time_index_) {
      time_index_ = -1;
      time_column_.clear();
      time_name_ = nullptr;
    }
  }
  value_column_ = value_columns_.front();
  values_.resize(value_indices_.size());
  return true;
}

bool TextRecordParser::ResolveColumn(const std::string& spec, const std::vector<std::string>& names,
                                     bool header, int* index) {
  const auto list = [&] {
    std::string out;
    for (std::size_t i = 0; i < names.size(); ++i) {
      out += (i ? ", " : "") + (header ? Shown(names[i]) : "") + (header ? " = " : "column ") +
             std::to_string(i);
    }
    return out;
  };
  *index = -1;
  if (spec.empty()) {
    *index = time_index_ == 0 ? 1 : 0;
    if (*index >= static_cast<int>(names.size())) {
      return Fail("no data column besides the time column '" + time_column_ + "'");
    }
    return true;
  }
  error_is_usage_ = true;
  if (AllDigits(spec)) {
    const auto [end, ec] = std::from_chars(spec.data(), spec.data() + spec.size(), *index);
    if (ec != std::errc() || *index >= static_cast<int>(names.size())) {
      return Fail("--column " + spec + ": the " + (header ? "header" : "first data row") +
                  " has " + std::to_string(names.size()) + " column(s), 0-based (" + list() + ")");
    }
    error_is_usage_ = false;
    return true;
  }
  if (!header) {
    return Fail("--column " + Shown(spec) +
                ": the file has no header row, so columns have no names; give a 0-based index");
  }
  for (std::size_t i = 0; i < names.size() && *index < 0; ++i) {
    if (names[i] == spec) *index = static_cast<int>(i);
  }
  if (*index < 0) {
    int matches = 0;
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (EqualsIgnoreCase(names[i], spec)) {
        *index = static_cast<int>(i);
        ++matches;
      }
    }
    if (matches > 1) *index = -1;
  }
  if (*index < 0) return Fail("--column " + Shown(spec) + ": no such column (" + list() + ")");
  error_is_usage_ = false;
  return true;
}

bool TextRecordParser::ParseLine(std::string_view line) {
  ++line_;
  if (line_ == 1 && line.substr(0, 3) == "\xEF\xBB\xBF") line.remove_prefix(3);
  if (line.find('\0') != std::string_view::npos) {
    return Fail("line " + std::to_string(line_) +
                " has a NUL byte: not a text record (raw samples? use --format f32|f64)");
  }
  if (const std::size_t hash = line.find('#'); hash != std::string_view::npos) {
    if (data_rows_ == 0 && probe_.empty()) KeepLeadingComment(line.substr(hash + 1));
    line = line.substr(0, hash);
  }
  if (Trim(line).empty()) return true;

  if (!format_known_) {
    format_known_ = true;
    delimiter_ = line.find(',') != std::string_view::npos    ? ','
                 : line.find('\t') != std::string_view::npos ? '\t'
                 : line.find(';') != std::string_view::npos  ? ';'
                                                             : ' ';
    Split(line, &fields_);
    if (delimiter_ == '\t') {
      // Tabs used for alignment among spaces ("1  2\t3") mean whitespace columns, not TSV.
      for (std::string_view f : fields_) {
        if (f.find(' ') != std::string_view::npos) delimiter_ = ' ';
      }
      if (delimiter_ == ' ') Split(line, &fields_);
    }
    bool header = false;
    double ignored;
    for (std::string_view f : fields_) header |= !ParseNumberField(f, &ignored);
    if (!ChooseColumns(fields_, header)) return false;
    if (header) return true;
    // Without a header the first column may be time: hold rows until that is decided.
    bool data_in_first = false;
    for (std::size_t k = 0; k < value_indices_.size(); ++k) {
      data_in_first |= !column_specs_[k].empty() && value_indices_[k] == 0;
    }
    probing_ = fields_.size() >= 2 && !data_in_first;
  } else {
    Split(line, &fields_);
  }
  if (probing_) {
    probe_.emplace_back(line_, std::string(line));
    if (static_cast<int>(probe_.size()) < kTimeProbeRows) return true;
    return DecideHeaderlessTime();
  }
  return ParseDataRow(line_);
}

bool TextRecordParser::DecideHeaderlessTime() {
  probing_ = false;
  bool increasing = probe_.size() >= 2;
  double previous = -std::numeric_limits<double>::infinity();
  for (const auto& [line, text] : probe_) {
    Split(text, &fields_);
    double t = 0.0;
    if (fields_.empty() || !ParseNumberField(fields_[0], &t) || !std::isfinite(t) ||
        !(t > previous)) {
      increasing = false;
      break;
    }
    previous = t;
  }
  if (increasing) {
    static constexpr TimeColumnName kHeaderlessTime{kHeaderlessTimeName, 1.0, false};
    time_index_ = 0;
    time_column_ = std::string(kHeaderlessTimeName);
    time_name_ = &kHeaderlessTime;
    time_guessed_ = true;
    if (column_spec_.empty()) {
      value_index_ = 1;
      value_indices_.front() = 1;
      value_column_ = "column 1";
      value_columns_.front() = value_column_;
    }
  }
  std::vector<std::pair<std::int64_t, std::string>> rows = std::move(probe_);
  probe_.clear();
  for (const auto& [line, text] : rows) {
    Split(text, &fields_);
    if (!ParseDataRow(line)) return false;
  }
  return true;
}

void TextRecordParser::KeepLeadingComment(std::string_view comment) {
  // A preamble of many thousand lines is not metadata; keep the memory bounded.
  static constexpr std::size_t kMaxLeadingComments = 256;
  const std::size_t colon = comment.find(':');
  if (colon == std::string_view::npos || leading_comments_.size() >= kMaxLeadingComments) return;
  const std::string_view key = Trim(comment.substr(0, colon));
  if (key.empty()) return;
  leading_comments_.emplace_back(std::string(key), std::string(Trim(comment.substr(colon + 1))));
}

std::string TextRecordParser::LeadingComment(std::string_view key) const {
  for (auto it = leading_comments_.rbegin(); it != leading_comments_.rend(); ++it) {
    if (EqualsIgnoreCase(it->first, key)) return it->second;
  }
  return "";
}

std::string TextRecordParser::TimeColumnPhrase(std::string_view time_column) {
  if (time_column == kHeaderlessTimeName) return "time column 0";
  return "time column " + std::string(time_column);
}

bool TextRecordParser::ParseDataRow(std::int64_t line_no) {
  int needed = time_index_ + 1;
  for (int index : value_indices_) needed = std::max(needed, index + 1);
  if (static_cast<int>(fields_.size()) < needed) {
    std::string columns;
    for (const std::string& c : value_columns_) columns += (columns.empty() ? "" : ", ") + Shown(c);
    return Fail("line " + std::to_string(line_no) + " has " + std::to_string(fields_.size()) +
                " field(s); column " + columns +
                (time_index_ >= 0 ? " and " + TimeColumnPhrase(time_column_) : std::string()) + " need " +
                std::to_string(needed));
  }
  TextRow row;
  row.line = line_no;
  for (std::size_t k = 0; k < value_indices_.size(); ++k) {
    const int index = value_indices_[k];
    if (!ParseNumberField(fields_[index], &values_[k])) {
      return Fail("line " + std::to_string(line_no) + ": column " + Shown(value_columns_[k]) + ": '" +
                  Shown(Trim(fields_[index])) + "' is not a number");
    }
  }
  row.value = values_.front();
  row.values = values_;
  if (time_index_ >= 0) {
    row.has_time = true;
    if (!ParseTimeField(fields_[time_index_], &row.time)) {
      return Fail("line " + std::to_string(line_no) + ": " + TimeColumnPhrase(time_column_) + ": '" +
                  Shown(Trim(fields_[time_index_])) + "' is not a number");
    }
  }
  ++data_rows_;
  if (!sink_(row)) {
    failed_ = true;
    return false;
  }
  return true;
}

}  // namespace allanlab::app
