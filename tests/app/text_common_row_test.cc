// Rows of the common shape are read in one pass (app/input/text_common_row.cc); every other line
// by the general line parser. Fed one byte at a time, no line is whole in a chunk, so the general
// parser reads them all: the two must give the same rows, values and errors, bit for bit, on rows
// of every shape, including numbers at the edges of the plain-decimal shortcut.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "app/input/plain_decimal.h"
#include "app/input/text_record_parser.h"

namespace allanlab::app {
namespace {

struct Row {
  std::int64_t line = 0;
  std::vector<double> values;
  bool has_time = false;
  double time = 0.0;
};

struct Result {
  bool ok = false;
  std::string error;
  std::vector<Row> rows;
};

Result Parse(const std::string& text, std::vector<std::string> columns, std::size_t chunk) {
  Result r;
  TextRecordParser parser(std::move(columns), nullptr, [&](const TextRow& row) {
    r.rows.push_back({row.line, {row.values.begin(), row.values.end()}, row.has_time, row.time});
    return true;
  });
  r.ok = true;
  for (std::size_t i = 0; r.ok && i < text.size(); i += chunk) {
    r.ok = parser.Feed(std::string_view(text).substr(i, chunk));
  }
  if (r.ok) r.ok = parser.Finish();
  r.error = parser.error();
  return r;
}

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void ExpectSame(const Result& fast, const Result& general, const std::string& what) {
  ASSERT_EQ(fast.ok, general.ok) << what << ": " << fast.error << " / " << general.error;
  ASSERT_EQ(fast.error, general.error) << what;
  ASSERT_EQ(fast.rows.size(), general.rows.size()) << what;
  for (std::size_t i = 0; i < fast.rows.size(); ++i) {
    const Row& a = fast.rows[i];
    const Row& b = general.rows[i];
    ASSERT_EQ(a.line, b.line) << what << ", row " << i;
    ASSERT_EQ(a.has_time, b.has_time) << what << ", line " << a.line;
    ASSERT_TRUE(SameBits(a.time, b.time)) << what << ", line " << a.line << ": " << a.time << " " << b.time;
    ASSERT_EQ(a.values.size(), b.values.size());
    for (std::size_t k = 0; k < a.values.size(); ++k) {
      ASSERT_TRUE(SameBits(a.values[k], b.values[k]))
          << what << ", line " << a.line << ": " << a.values[k] << " " << b.values[k];
    }
  }
}

// A number in one of many shapes: plain decimals of 1 to 22 digits, with or without a fraction
// and an exponent of 1 to 5 digits, signed or not; hex, nan, a missing value, text.
std::string RandomNumber(std::mt19937_64& rng) {
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
std::string RandomField(std::mt19937_64& rng, bool errors) {
  double ignored;
  std::string s = RandomNumber(rng);
  while (!errors && !ParseNumberField(s, &ignored)) s = RandomNumber(rng);
  return s;
}

// Rows of many shapes; with `errors`, also rows the parse stops at (a bad number, a NUL byte,
// too few fields), rarely enough that most of the record is read first.
std::string RandomRecord(std::mt19937_64& rng, int rows, const std::string& header, bool errors) {
  std::string text = header + "\n";
  for (int k = 0; k < rows; ++k) {
    const unsigned shape = rng() % (errors ? 400 : 50);
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
    if (errors && shape == 8) row = time + "," + RandomField(rng, errors);  // too few fields for column b
    if (errors && shape == 9) row += std::string(",a\0b", 4);
    text += row;
    text += rng() % 5 == 0 ? "\r\n" : "\n";
  }
  return text;
}

TEST(TextCommonRowTest, RowsOfEveryShapeReadAsTheGeneralParserReadsThem) {
  std::mt19937_64 rng(11);
  int failed_records = 0;
  for (int record = 0; record < 300; ++record) {
    const std::string text = RandomRecord(rng, 300, "t_s,a,b", record % 2 == 1);
    for (const std::vector<std::string>& columns :
         {std::vector<std::string>{"a"}, std::vector<std::string>{"b", "a"}, std::vector<std::string>{"b"}}) {
      const Result fast = Parse(text, columns, text.size());
      const Result general = Parse(text, columns, 1);
      failed_records += !general.ok;
      ExpectSame(fast, general, "record " + std::to_string(record) + ", " + columns.front());
      ExpectSame(Parse(text, columns, 61), general, "chunks of 61, record " + std::to_string(record));
    }
  }
  // Both outcomes were exercised: records that read whole and records that stop at a bad field.
  EXPECT_GT(failed_records, 0);
  EXPECT_LT(failed_records, 600);
}

// Records that read whole: only the number shapes a parse accepts, in long runs of common rows,
// headerless (time found by its increase), tab-separated, and with the time column last.
TEST(TextCommonRowTest, LongRecordsOfGoodRowsReadAsTheGeneralParserReadsThem) {
  std::mt19937_64 rng(12);
  for (int record = 0; record < 40; ++record) {
    const char delimiter = record % 2 ? '\t' : ',';
    const bool headerless = record % 4 == 1;
    const bool time_last = record % 4 == 2;
    std::string text = headerless ? "" : time_last ? std::string("a") + delimiter + "t" : std::string("t") + delimiter + "a";
    if (!headerless) text += "\n";
    for (int k = 0; k < 3000; ++k) {
      std::string value;
      double ignored;
      do {
        value = RandomNumber(rng);
      } while (!ParseNumberField(value, &ignored) || value.empty() || value == "nan" || value == "NA");
      const std::string time = std::to_string(k + 1) + "." + std::to_string(rng() % 1000) + (rng() % 7 ? "" : "e0");
      text += time_last ? value + delimiter + time : time + delimiter + value;
      text += "\n";
    }
    const std::vector<std::string> columns = {headerless ? "1" : "a"};
    const Result general = Parse(text, columns, 1);
    ASSERT_TRUE(general.ok) << general.error;
    ExpectSame(Parse(text, columns, text.size()), general, "record " + std::to_string(record));
  }
}

// The shortcut's numbers are the correctly rounded doubles strtod gives, and it declines what it
// cannot read exactly (more than 19 digits, 2^53 + 1, powers of ten beyond 22) or at all.
TEST(PlainDecimalTest, AgreesWithStrtodAndDeclinesTheRest) {
  std::mt19937_64 rng(13);
  int read = 0, declined = 0;
  for (int i = 0; i < 200000; ++i) {
    std::string s = RandomNumber(rng);
    if (!s.empty() && (s[0] == '-' || s[0] == '+')) s.erase(0, 1);
    double v = -1.0;
    if (ParsePlainDecimal(s, &v)) {
      ++read;
      char* end = nullptr;
      const double expected = std::strtod(s.c_str(), &end);
      ASSERT_EQ(*end, '\0') << s;
      ASSERT_TRUE(SameBits(v, expected)) << s << ": " << v << ", strtod " << expected;
    } else {
      ++declined;
      ASSERT_EQ(v, -1.0) << s;  // left alone
    }
  }
  EXPECT_GT(read, 80000);
  EXPECT_GT(declined, 10000);
  double v = 0.0;
  EXPECT_FALSE(ParsePlainDecimal("9007199254740993", &v));
  EXPECT_TRUE(ParsePlainDecimal("9007199254740992", &v));
  EXPECT_FALSE(ParsePlainDecimal("12345678901234567890", &v));
  EXPECT_FALSE(ParsePlainDecimal("1e23", &v));
  EXPECT_FALSE(ParsePlainDecimal("1e00001", &v));
  bool integral = false;
  const std::string text = "12.5e-3,";
  EXPECT_EQ(ScanPlainDecimal(text.data(), text.data() + text.size(), &v, &integral), text.data() + 7);
  EXPECT_EQ(v, 12.5e-3);
  EXPECT_FALSE(integral);
}

}  // namespace
}  // namespace allanlab::app
