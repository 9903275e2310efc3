#pragma once
// What a TextRecordParser gives for a text, logged for comparison, and random records to give it:
// for tests that two ways of reading (the common-row shortcut and the general line parser, one
// thread and two, rows one by one and in blocks) give the same rows, values and errors, bit for
// bit.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "app/input/text_record_parser.h"

namespace allanlab::testing_support {

struct LoggedRow {
  std::int64_t line = 0;
  std::vector<double> values;
  bool has_time = false;
  double time = 0.0;
};

struct ParseLog {
  bool ok = false;
  std::string error;
  std::vector<LoggedRow> rows;
  std::int64_t lines = 0;  // read, when the parse went through
  std::int64_t two_thread_chunks = 0;  // chunks the parser cut for its helper
};

// How ParseText reads: in two threads from chunks of `two_thread_min_bytes` on (0: one thread;
// TextRecordParser::UseTwoThreads); runs of common rows as blocks (PassRunsAsBlocks), logged row
// by row; with the sink stopping the parse at row `stop_after` (0: never).
struct ParseWay {
  std::size_t two_thread_min_bytes = 0;
  bool blocks = false;
  std::size_t stop_after = 0;
};

// Feeds `text` in chunks of `chunk` bytes, then Finish().
inline ParseLog ParseText(const std::string& text, std::vector<std::string> columns,
                          std::size_t chunk, ParseWay way = {}) {
  ParseLog log;
  const auto keep = [&](std::int64_t line, std::span<const double> values, bool has_time,
                        double time) {
    log.rows.push_back({line, {values.begin(), values.end()}, has_time, time});
    return way.stop_after == 0 || log.rows.size() < way.stop_after;
  };
  app::TextRecordParser parser(std::move(columns), nullptr, [&](const app::TextRow& row) {
    return keep(row.line, row.values, row.has_time, row.time);
  });
  if (way.blocks) {
    parser.PassRunsAsBlocks([&](const app::TextRowBlock& block) {
      EXPECT_EQ(block.values.size(), block.rows * block.width);
      EXPECT_EQ(block.times.size(), block.has_time ? block.rows : 0);
      for (std::size_t k = 0; k < block.rows; ++k) {
        if (!keep(block.first_line + static_cast<std::int64_t>(k),
                  block.values.subspan(k * block.width, block.width), block.has_time,
                  block.has_time ? block.times[k] : 0.0)) {
          return false;
        }
      }
      return true;
    });
  }
  if (way.two_thread_min_bytes > 0) parser.UseTwoThreads(way.two_thread_min_bytes);
  log.ok = true;
  for (std::size_t i = 0; log.ok && i < text.size(); i += chunk) {
    log.ok = parser.Feed(std::string_view(text).substr(i, chunk));
  }
  if (log.ok) log.ok = parser.Finish();
  log.error = parser.error();
  log.lines = parser.lines();
  log.two_thread_chunks = parser.two_thread_chunks();
  return log;
}

inline bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

inline void ExpectSameParse(const ParseLog& a, const ParseLog& b, const std::string& what) {
  ASSERT_EQ(a.ok, b.ok) << what << ": " << a.error << " / " << b.error;
  ASSERT_EQ(a.error, b.error) << what;
  if (a.ok) {
    ASSERT_EQ(a.lines, b.lines) << what;
  }
  ASSERT_EQ(a.rows.size(), b.rows.size()) << what;
  for (std::size_t i = 0; i < a.rows.size(); ++i) {
    const LoggedRow& x = a.rows[i];
    const LoggedRow& y = b.rows[i];
    ASSERT_EQ(x.line, y.line) << what << ", row " << i;
    ASSERT_EQ(x.has_time, y.has_time) << what << ", line " << x.line;
    ASSERT_TRUE(SameBits(x.time, y.time))
        << what << ", line " << x.line << ": " << x.time << " " << y.time;
    ASSERT_EQ(x.values.size(), y.values.size());
    for (std::size_t k = 0; k < x.values.size(); ++k) {
      ASSERT_TRUE(SameBits(x.values[k], y.values[k]))
          << what << ", line " << x.line << ": " << x.values[k] << " " << y.values[k];
    }
  }
}

// A number in one of many shapes: plain decimals of 1 to 22 digits, with or without a fraction
// and an exponent of 1 to 5 digits, signed or not; hex, nan, a missing value, text.
inline std::string RandomNumber(std::mt19937_64& rng) {
  auto digits = [&](int n) {
    std::string s;
    for (int i = 0; i < n; ++i) s += static_cast<char>('0' + rng() % 10);
    return s;
  };
  switch (rng() % 40) {
    case 0: return "0x1.8p3";
    case 1: return "nan";
    case 2: return "";
    case 3: return "NA";
    case 4: return "1.";
    case 5: return ".5";
    case 6: return "-";
    case 7: return "1e";
    case 8: return "9007199254740993";
    case 9: return "9007199254740992.0";
    case 10: return "4.5e-22";
    case 11: return "4.5e-23";
    case 12: return "x";
    default: break;
  }
  std::string s;
  const unsigned sign = rng() % 6;
  if (sign == 0) s += '-';
  if (sign == 1) s += '+';
  s += digits(1 + static_cast<int>(rng() % (rng() % 4 == 0 ? 22 : 9)));
  if (rng() % 3 != 0) s += "." + digits(1 + static_cast<int>(rng() % (rng() % 4 == 0 ? 20 : 10)));
  if (rng() % 3 == 0) {
    s += rng() % 2 ? 'e' : 'E';
    const unsigned exponent_sign = rng() % 3;
    if (exponent_sign == 1) s += '-';
    if (exponent_sign == 2) s += '+';
    s += digits(1 + static_cast<int>(rng() % (rng() % 8 == 0 ? 5 : 2)));
  }
  return s;
}

// A number ParseNumberField reads (errors false), or any of RandomNumber's.
inline std::string RandomField(std::mt19937_64& rng, bool errors) {
  double ignored;
  std::string s = RandomNumber(rng);
  while (!errors && !app::ParseNumberField(s, &ignored)) s = RandomNumber(rng);
  return s;
}

// Rows of many shapes under a header (columns t_s, a, b); with `errors`, also rows the parse
// stops at (a bad number, a NUL byte, too few fields), rarely enough that most of the record is
// read first. One row in `shapes` (at least 11) is not a plain common row.
inline std::string RandomRecord(std::mt19937_64& rng, int rows, const std::string& header,
                                bool errors, unsigned shapes = 50) {
  std::string text = header + "\n";
  for (int k = 0; k < rows; ++k) {
    const unsigned shape = rng() % (errors ? 8 * shapes : shapes);
    std::string time = std::to_string(k) + "." + std::to_string(rng() % 100);
    if (shape == 0) time = std::to_string(k);  // an integer stamp: the origin of the rest
    if (shape == 1) time = RandomField(rng, errors);
    std::string row = time + "," + RandomField(rng, errors) + "," + RandomField(rng, errors);
    if (shape == 2) row = "# comment, 1, 2";
    if (shape == 3) row = "";
    if (shape == 4) row = time + ", " + RandomField(rng, errors) + " ,1";
    if (shape == 5) row = time + ",\"" + RandomField(rng, errors) + "\",1";
    if (shape == 6) row += ",extra,fields";
    if (shape == 7) row += " # trailing";
    if (shape == 10) row = time + ",1.5\r,2";
    // Too few fields for column b.
    if (errors && shape == 8) row = time + "," + RandomField(rng, errors);
    if (errors && shape == 9) row += std::string(",a\0b", 4);
    text += row;
    text += rng() % 5 == 0 ? "\r\n" : "\n";
  }
  return text;
}

}  // namespace allanlab::testing_support
