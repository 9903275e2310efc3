#pragma once
// Incremental parser of a delimited text record: CSV, TSV, ';'-separated or whitespace-separated
// columns, '#' comments, an optional header row. Bytes go in by chunks of any size (the split
// never changes the result); each data row comes out as one value of the chosen column, plus the
// time column's value when the header names one. The parser only extracts: what a value means
// (finite or not, time steps, sample rate) is decided by the caller (app/input/record_reader.h).
//
// Format rules, decided on the first line that is not blank or a comment:
//  - delimiter: ',' if that line has one, else tab (unless a tab-separated field holds a space:
//    then the tabs only align columns), else ';', else runs of spaces/tabs;
//  - that line is a header when any field is neither a number nor a missing-value marker;
//  - '#' starts a comment anywhere on a line; '\r' line ends, a UTF-8 BOM, spaces around fields
//    and double quotes around a field ("Gyro_X") are ignored;
//  - numbers are C-locale decimal or hex floats, a leading '+' allowed; "nan", "inf",
//    "infinity" (any case, signed), "NA" and an empty field are read as NaN (missing values,
//    which the caller may drop), a number beyond the double range as +-inf;
//  - a NUL byte or a line longer than kMaxLineBytes means the file is not text;
//  - `# key: value` comment lines before the first data row are kept (LeadingComment): that is
//    how `allanlab simulate` states the units and the sample rate of what follows;
//  - without a header, a first column whose values strictly increase over the first
//    kTimeProbeRows data rows is the time column (the two-column `time value` layout of Stable32
//    and SigmaTheta), in seconds, unless --column chose it as the data.
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace allanlab {
class PieceSharing;
}

namespace allanlab::app {

// The header names that mark a time column (compared case-insensitively) and the unit each
// implies. Bare names (t, time, timestamp) are taken as seconds unless the caller is told
// otherwise: app/input/record_reader.h rejects a bare-named column whose step is implausible as seconds.
// "%time" is the nanosecond receive time `rostopic echo -p` writes.
struct TimeColumnName {
  std::string_view name;
  double seconds_per_unit;
  bool unit_in_name;
};
inline constexpr TimeColumnName kTimeColumnNames[] = {
    {"t", 1.0, false},        {"t_s", 1.0, true},       {"time", 1.0, false},
    {"time_s", 1.0, true},    {"timestamp", 1.0, false}, {"timestamp_s", 1.0, true},
    {"t_ms", 1e-3, true},     {"time_ms", 1e-3, true},  {"timestamp_ms", 1e-3, true},
    {"t_us", 1e-6, true},     {"time_us", 1e-6, true},  {"timestamp_us", 1e-6, true},
    {"t_ns", 1e-9, true},     {"time_ns", 1e-9, true},  {"timestamp_ns", 1e-9, true},
    {"%time", 1e-9, true}};

struct TextRow {
  std::int64_t line = 0;  // 1-based physical line number in the (decompressed) text
  double value = 0.0;     // may be NaN or +-inf; the first of `values`
  // Every chosen value column, in the order asked (one entry with the one-column constructor).
  // Valid during the sink call only.
  std::span<const double> values;
  bool has_time = false;
  // In the time column's own unit, when has_time; may be non-finite. Integer time stamps are
  // given relative to the first row's, exactly: a 19-digit nanosecond stamp does not fit a
  // double, but its steps do.
  double time = 0.0;
};

// Data rows of the common shape (plain decimals between single delimiters) on consecutive lines,
// first_line, first_line + 1, ...: what `rows` RowSink calls would be given, at once. Valid during
// the sink call only.
struct TextRowBlock {
  std::int64_t first_line = 0;
  std::size_t rows = 0;
  std::size_t width = 0;           // values per row: TextRow::values.size()
  std::span<const double> values;  // rows * width, row by row
  bool has_time = false;
  std::span<const double> times;  // one per row, when has_time
};

class TextRecordParser {
 public:
  // Called for each data row; returning false stops the parse (Feed/Finish then return false
  // with error() empty: the sink keeps its own reason).
  using RowSink = std::function<bool(const TextRow&)>;

  static constexpr std::size_t kMaxLineBytes = 1 << 20;
  // Rows of a headerless file read before deciding whether its first column is time: 32 noisy
  // values rise in order by chance with probability 1/32! (~4e-36).
  static constexpr int kTimeProbeRows = 32;
  // The name a headerless time column is given (in messages and RecordInfo::time_column).
  static constexpr std::string_view kHeaderlessTimeName = "column 0";
  // How messages name a time column: "time column t_s", or "time column 0" for a headerless file.
  static std::string TimeColumnPhrase(std::string_view time_column);

  // `column`: the --column text, a header name or a 0-based index (all digits); empty picks the
  // first column that is not the time column. Names are matched exactly, else case-insensitively
  // when that is unambiguous.
  explicit TextRecordParser(std::string column, RowSink sink);

  // Several value columns read in one pass: `columns` are resolved each as the one-column
  // constructor's (none may be empty or repeated); or, when `columns` is empty, `choose` picks
  // them from the header's names (the time column's index, -1 for none, given to skip it).
  // Without a header row the chooser sees empty names.
  using ColumnChooser = std::function<bool(const std::vector<std::string>& names, int time_index,
                                           std::vector<std::string>* columns, std::string* why)>;
  TextRecordParser(std::vector<std::string> columns, ColumnChooser choose, RowSink sink);
  ~TextRecordParser();

  // From now on, runs of rows of the common shape go to `sink` in blocks instead of to the RowSink
  // row by row (every other row still goes to the RowSink): the same rows in the same order, for
  // a caller that checks many rows in one pass. Returning false stops the parse as the RowSink's
  // false does.
  using RowBlockSink = std::function<bool(const TextRowBlock&)>;
  void PassRunsAsBlocks(RowBlockSink sink);

  // From now on, a Feed() chunk of at least `min_bytes` is read in two threads where its rows are
  // of the common shape (plain decimals between single delimiters, app/input/text_common_row.cc):
  // a helper thread reads the rows of its last part while this thread reads the first part's and
  // passes them on. Rows reach the sink from this thread only, in file order, and are the rows,
  // line numbers and errors one thread gives: only the time taken differs. The helper starts at
  // the first chunk so cut, so a record smaller than `min_bytes` starts none; from about a MB a
  // chunk is worth the helper's wake-up.
  static constexpr std::size_t kTwoThreadMinBytes = std::size_t{1} << 20;
  void UseTwoThreads(std::size_t min_bytes = kTwoThreadMinBytes);
  // Chunks cut for the helper so far (for tests).
  std::int64_t two_thread_chunks() const { return two_thread_chunks_; }

  // Parses the complete lines in `chunk` (a partial last line is kept for the next call).
  // Returns false on the first format error (error() says which line and why) or when the sink
  // stopped; after that the parser ignores further input.
  bool Feed(std::string_view chunk);
  // Parses the last line if it has no newline. Call once, after the last Feed().
  bool Finish();

  const std::string& error() const { return error_; }
  // The error is about the --column choice (the command line), not about the file's content.
  bool error_is_usage() const { return error_is_usage_; }
  // Known once the first non-comment line has been seen.
  bool has_header() const { return has_header_; }
  char delimiter() const { return delimiter_; }  // ' ' for whitespace
  // The chosen column: its header name, or "column K" without a header; and its 0-based index.
  const std::string& value_column() const { return value_column_; }
  int value_column_index() const { return value_index_; }
  // Every chosen column (their names as value_column()); known with has_header().
  const std::vector<std::string>& value_columns() const { return value_columns_; }
  // The time column's header name, empty when there is none, and its entry in kTimeColumnNames.
  const std::string& time_column() const { return time_column_; }
  const TimeColumnName* time_column_name() const { return time_name_; }
  // True when the time column is a headerless first column found by its increasing values.
  bool time_column_guessed() const { return time_guessed_; }
  std::int64_t lines() const { return line_; }  // physical lines read so far
  std::int64_t data_rows() const { return data_rows_; }
  // The value of the last `# key: value` comment line before the first data row whose key matches
  // `key` case-insensitively (keys are trimmed); empty when there is none.
  std::string LeadingComment(std::string_view key) const;

 private:
  // Feed(), with `two_threads` saying whether a large chunk may be cut for the helper.
  bool FeedLines(std::string_view chunk, bool two_threads);
  bool ParseLine(std::string_view line);

  // The fields of a row of the common shape, fixed once the columns are chosen (so the helper
  // thread reads it while this one parses): each field's role up to the last one read, a value
  // column's slot in values_, the time, or skipped.
  static constexpr int kTimeField = -1;
  static constexpr int kSkippedField = -2;
  struct CommonRowShape {
    char delimiter = ',';
    std::vector<int> field_roles;
    std::size_t values = 0;  // value columns per row
  };
  // Rows of the common shape read one after another from the start of a text, to be passed on.
  struct CommonRows {
    std::vector<double> values;  // CommonRowShape::values per row
    std::vector<double> times;   // one per row
    std::size_t rows = 0;
    std::size_t bytes = 0;  // their lines' bytes, newlines included
  };
  // Rows of the common shape (app/input/text_common_row.cc). ScanCommonRow reads the line at p
  // (values into values[slot], the time into *time) and returns its end, after the newline;
  // nullptr when the line is not of that shape (or not whole before `end`), which ParseLine then
  // reads. ReadCommonRows reads such lines until one is not; both only read the shape and the
  // text. ReadCommonRow reads one at the start of `chunk` and passes it on: the bytes of its
  // line, 0 when it is not of that shape.
  static const char* ScanCommonRow(const CommonRowShape& shape, const char* p, const char* end,
                                   double* values, double* time);
  static void ReadCommonRows(const CommonRowShape& shape, std::string_view text, CommonRows* rows);
  std::size_t ReadCommonRow(std::string_view chunk);
  // The run of common rows at the start of `chunk` read and passed on (a block to the block sink,
  // if any): the bytes of their lines, 0 when the first line is not of that shape.
  std::size_t ReadCommonRun(std::string_view chunk);
  // The next line's row, or the next lines' rows (as a block when there is a block sink), to the
  // sink; false when the sink stopped the parse.
  bool PassCommonRow(std::span<const double> values, double time);
  bool PassCommonRows(const CommonRows& rows);
  // Whether rows can be of the common shape now (the columns chosen, no held rows, a delimiter,
  // no integer time origin); sets up common_shape_ the first time.
  bool CommonRowsPossible();
  // The lines at the start of `chunk` (pending_ empty, common rows possible) read in two threads
  // (app/input/text_two_thread_rows.cc): the bytes read, up to the first line of the last piece
  // that is not a common row; 0 when the chunk has no line start to cut at.
  std::size_t ReadChunkInTwoThreads(std::string_view chunk);
  // Whole lines read in this thread: runs of common rows, and each line between them as
  // FeedLines reads it.
  bool ReadLinesInThisThread(std::string_view lines);
  bool ParseDataRow(std::int64_t line);
  bool DecideHeaderlessTime();
  void KeepLeadingComment(std::string_view comment);
  bool ChooseColumns(const std::vector<std::string_view>& first_fields, bool header);
  bool ResolveColumn(const std::string& spec, const std::vector<std::string>& names, bool header,
                     int* index);
  bool Fail(std::string message);
  bool ParseTimeField(std::string_view field, double* time);
  void Split(std::string_view line, std::vector<std::string_view>* fields) const;

  std::string column_spec_;  // the first of column_specs_
  std::vector<std::string> column_specs_;
  ColumnChooser choose_;
  RowSink sink_;
  RowBlockSink block_sink_;  // may be empty
  std::string pending_;  // the incomplete last line of the previous chunk
  std::string error_;
  bool failed_ = false;
  bool error_is_usage_ = false;
  bool finished_ = false;
  bool format_known_ = false;
  bool has_header_ = false;
  char delimiter_ = ',';
  std::string value_column_;
  int value_index_ = -1;
  std::vector<std::string> value_columns_;
  std::vector<int> value_indices_;
  std::vector<double> values_;  // the current row's
  std::string time_column_;
  int time_index_ = -1;
  const TimeColumnName* time_name_ = nullptr;
  bool time_origin_set_ = false;
  std::int64_t time_origin_ = 0;  // the first integer time stamp
  std::int64_t line_ = 0;
  std::int64_t data_rows_ = 0;
  std::vector<std::string_view> fields_;  // reused per line
  CommonRowShape common_shape_;
  // The rows of a run read in this thread (ReadCommonRun). Reading in two threads: the smallest
  // chunk cut (0: never), the helper, the rows of each piece.
  CommonRows run_rows_;
  std::size_t two_thread_min_bytes_ = 0;
  std::unique_ptr<PieceSharing> helper_;
  std::vector<CommonRows> helper_rows_;
  std::int64_t two_thread_chunks_ = 0;
  // Headerless time probe: the first rows (line number, text) held until the decision.
  bool probing_ = false;
  bool time_guessed_ = false;
  std::vector<std::pair<std::int64_t, std::string>> probe_;
  std::vector<std::pair<std::string, std::string>> leading_comments_;
};

// Reads one field as a number by the rules above. Returns false when the text is not a number
// and not a missing-value marker.
bool ParseNumberField(std::string_view field, double* value);

}  // namespace allanlab::app
