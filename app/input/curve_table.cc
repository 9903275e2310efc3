#include "app/input/curve_table.h"

#include <cmath>
#include <memory>
#include <string_view>

#include "app/input/byte_source.h"
#include "app/reports/provenance.h"
#include "app/failure.h"
#include "app/input/text_record_parser.h"
#include "common/number_text.h"

namespace allanlab::app {
namespace {

std::string_view Trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  if (s.size() >= 2 && s.front() == '"' && s.back() == '"') s = Trim(s.substr(1, s.size() - 2));
  return s;
}

std::string Lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
  return out;
}

std::vector<std::string_view> Split(std::string_view line, char delimiter) {
  std::vector<std::string_view> out;
  if (delimiter == ' ') {
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
      const std::size_t start = i;
      while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
      if (i > start) out.push_back(line.substr(start, i - start));
    }
    return out;
  }
  std::size_t start = 0;
  while (true) {
    const std::size_t end = line.find(delimiter, start);
    out.push_back(Trim(line.substr(start, end == std::string_view::npos ? end : end - start)));
    if (end == std::string_view::npos) return out;
    start = end + 1;
  }
}

class TableReader {
 public:
  TableReader(const CurveTableOptions& o, CurveTable* t) : o_(o), t_(t) {}

  bool Run(CurveTableError* error) {
    const std::string shown = o_.path == "-" ? "stdin" : o_.path;
    in_ = shown + ": ";
    std::unique_ptr<ByteSource> source;
    std::string why;
    if (!OpenByteSource(o_.path, &source, &why)) return Fail(error, kExitRuntimeError, why);
    estimators::AvarCurve& c = t_->curve;
    c = estimators::AvarCurve();
    c.sample_clock = SampleClock::FromRateHz(o_.sample_rate_hz);
    c.num_samples = static_cast<std::int64_t>(std::llround(o_.record_length_s * o_.sample_rate_hz));
    c.estimator = sim::AvarEstimatorKind::kOverlapping;
    std::vector<char> chunk(1 << 16);
    std::string pending;
    while (true) {
      std::size_t got = 0;
      if (!source->Read(chunk, &got, &why)) return Fail(error, kExitRuntimeError, why);
      if (got == 0) break;
      pending.append(chunk.data(), got);
      std::size_t start = 0;
      for (std::size_t nl; (nl = pending.find('\n', start)) != std::string::npos; start = nl + 1) {
        if (!Line(std::string_view(pending).substr(start, nl - start), error)) return false;
      }
      pending.erase(0, start);
    }
    if (!pending.empty() && !Line(pending, error)) return false;
    if (tau_col_ < 0) return Fail(error, kExitRuntimeError, in_ + "no header row (tau_s and " + o_.column + ")");
    if (c.m.empty()) {
      return Fail(error, kExitRuntimeError,
                  in_ + "no usable rows in " + o_.column + " (" + std::to_string(t_->rows) +
                      " read" + (t_->skipped.empty() ? "" : "; " + t_->skipped.front()) + ")");
    }
    return true;
  }

 private:
  bool Fail(CurveTableError* error, int code, std::string message) {
    *error = {code, std::move(message)};
    return false;
  }

  bool Line(std::string_view line, CurveTableError* error) {
    ++line_;
    if (const std::size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    if (Trim(line).empty()) return true;
    if (tau_col_ < 0) return Header(line, error);
    const std::vector<std::string_view> cells = Split(line, delimiter_);
    const std::string where = in_ + "line " + std::to_string(line_) + ": ";
    if (static_cast<int>(cells.size()) <= std::max(tau_col_, value_col_)) {
      return Fail(error, kExitRuntimeError, where + std::to_string(cells.size()) + " column(s), the header has more");
    }
    double tau = 0.0, value = 0.0;
    if (!ParseNumberField(cells[tau_col_], &tau) || !std::isfinite(tau) || !(tau > 0.0)) {
      return Fail(error, kExitRuntimeError, where + "tau '" + std::string(Trim(cells[tau_col_])) + "' is not a number > 0");
    }
    if (!ParseNumberField(cells[value_col_], &value) || !std::isfinite(value) || !(value > 0.0)) {
      return Fail(error, kExitRuntimeError, where + o_.column + " '" + std::string(Trim(cells[value_col_])) + "' is not a number > 0");
    }
    ++t_->rows;
    estimators::AvarCurve& c = t_->curve;
    const std::int64_t m = std::llround(tau / c.sample_clock.period_s());
    const std::string at = "line " + std::to_string(line_) + ": tau " + ShortestDecimal(tau) + " s";
    if (m < 1) {
      t_->skipped.push_back(at + " is below the sample period " + ShortestDecimal(c.sample_clock.period_s()) + " s");
      return true;
    }
    if (2 * m > c.num_samples) {
      t_->skipped.push_back(at + " is beyond half the record (" + ShortestDecimal(o_.record_length_s) + " s)");
      return true;
    }
    if (!c.m.empty() && m <= c.m.back()) {
      t_->skipped.push_back(at + " is not above the previous row's (m = " + std::to_string(m) + ")");
      return true;
    }
    c.m.push_back(m);
    c.tau_s.push_back(static_cast<double>(m) * c.sample_clock.period_s());
    const double si = t_->variance ? ToRadPerSecond(o_.unit, ToRadPerSecond(o_.unit, value))
                                   : ToRadPerSecond(o_.unit, value);
    c.avar.push_back(t_->variance ? si : si * si);
    // Initial weights only (the GLS fit uses the model covariance): white-noise EDF.
    c.edf.push_back(std::max(1.0, static_cast<double>(c.num_samples) / static_cast<double>(m) - 1.0));
    return true;
  }

  bool Header(std::string_view line, CurveTableError* error) {
    delimiter_ = line.find(',') != std::string_view::npos    ? ','
                 : line.find('\t') != std::string_view::npos ? '\t'
                 : line.find(';') != std::string_view::npos  ? ';'
                                                             : ' ';
    const std::vector<std::string_view> names = Split(line, delimiter_);
    std::string list;
    for (std::size_t i = 0; i < names.size(); ++i) {
      const std::string name = Lower(Trim(names[i]));
      list += (i ? ", " : "") + std::string(Trim(names[i]));
      if (tau_col_ < 0 && (name == "tau_s" || name == "tau")) tau_col_ = static_cast<int>(i);
      if (value_col_ < 0 && Trim(names[i]) == o_.column) value_col_ = static_cast<int>(i);
    }
    for (std::size_t i = 0; i < names.size() && value_col_ < 0; ++i) {
      if (Lower(Trim(names[i])) == Lower(o_.column)) value_col_ = static_cast<int>(i);
    }
    if (tau_col_ < 0 || value_col_ < 0) {
      return Fail(error, kExitUsageError,
                  in_ + "line " + std::to_string(line_) + ": the header needs a tau column (tau_s or tau) and " +
                      o_.column + " (--curve-column); it has " + list);
    }
    const std::string v = Lower(o_.column);
    t_->variance = v.rfind("avar", 0) == 0 || v.rfind("oavar", 0) == 0 || v.rfind("var", 0) == 0;
    return true;
  }

  const CurveTableOptions& o_;
  CurveTable* t_;
  std::string in_;
  std::int64_t line_ = 0;
  char delimiter_ = ',';
  int tau_col_ = -1;
  int value_col_ = -1;
};

}  // namespace

bool ReadCurveTable(const CurveTableOptions& options, CurveTable* table, CurveTableError* error) {
  *table = CurveTable();
  return TableReader(options, table).Run(error);
}

}  // namespace allanlab::app
