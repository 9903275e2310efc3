// libFuzzer target for the text record parser (app/input/text_record_parser.h) and the time-step
// checks it feeds (app/input/time_steps.h): any bytes, any column choice, any chunking.
//
// Besides crashes and sanitizer reports it checks the parser's promises that neither the split of
// the input into chunks nor reading it in two threads changes the result: the input is parsed
// whole, in chunks, and whole in two threads (every chunk of 64 bytes or more cut), and the runs
// must give the same rows, the same error and the same columns (else abort()).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "app/input/text_record_parser.h"
#include "app/input/time_steps.h"

namespace {

using allanlab::app::TextRecordParser;
using allanlab::app::TextRow;
using allanlab::app::TimeSteps;

struct Outcome {
  bool ok = false;
  std::string error;
  std::vector<TextRow> rows;
  std::string column, time_column;
  std::string time_error;
};

bool SameRow(const TextRow& a, const TextRow& b) {
  const auto same = [](double x, double y) { return x == y || (std::isnan(x) && std::isnan(y)); };
  return a.line == b.line && same(a.value, b.value) && a.has_time == b.has_time &&
         same(a.time, b.time);
}

Outcome Parse(std::string_view text, const std::string& column, std::size_t chunk,
              bool two_threads = false) {
  Outcome o;
  TimeSteps steps;
  TextRecordParser parser(column, [&](const TextRow& row) {
    // Rows come in file order.
    if (!o.rows.empty() && row.line <= o.rows.back().line) std::abort();
    o.rows.push_back(row);
    if (row.has_time && o.time_error.empty()) steps.Add(row.time, row.line, &o.time_error);
    return o.rows.size() < 100000;
  });
  if (two_threads) parser.UseTwoThreads(64);
  o.ok = true;
  for (std::size_t i = 0; o.ok && i < text.size(); i += chunk) {
    o.ok = parser.Feed(text.substr(i, chunk));
  }
  if (o.ok) o.ok = parser.Finish();
  o.error = parser.error();
  o.column = parser.value_column();
  o.time_column = parser.time_column();
  const TimeSteps::Summary summary = steps.Summarize();
  if (summary.irregular_steps < 0 || summary.irregular_steps > summary.samples) std::abort();
  if (summary.irregular_steps > 0) (void)TimeSteps::Describe(summary, o.time_column);
  return o;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  static const char* const kColumns[] = {"", "0", "1", "2", "17", "x", "t", "Gyro_X", "time"};
  const std::string column = kColumns[data[0] % (sizeof kColumns / sizeof kColumns[0])];
  const std::size_t chunk = 1 + data[1] % 61;
  const std::string_view text(reinterpret_cast<const char*>(data) + 2, size - 2);

  const Outcome whole = Parse(text, column, text.size() + 1);
  for (const Outcome& other :
       {Parse(text, column, chunk), Parse(text, column, text.size() + 1, true)}) {
    if (whole.ok != other.ok || whole.error != other.error || whole.column != other.column ||
        whole.time_column != other.time_column || whole.time_error != other.time_error ||
        whole.rows.size() != other.rows.size()) {
      std::abort();
    }
    for (std::size_t i = 0; i < whole.rows.size(); ++i) {
      if (!SameRow(whole.rows[i], other.rows[i])) std::abort();
    }
  }
  // A failed parse always says why, unless the sink stopped it (the 100000-row cap here).
  if (!whole.ok && whole.error.empty() && whole.rows.size() < 100000) std::abort();
  if (whole.error.find('\n') != std::string::npos) std::abort();  // messages are one line
  return 0;
}
