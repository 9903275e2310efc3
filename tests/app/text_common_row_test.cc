// Rows of the common shape are read in one pass (app/input/text_common_row.cc); every other line
// by the general line parser. Fed one byte at a time, no line is whole in a chunk, so the general
// parser reads them all: the two must give the same rows, values and errors, bit for bit, on rows
// of every shape, including numbers at the edges of the plain-decimal shortcut; and so must runs of
// common rows passed on as blocks (TextRecordParser::PassRunsAsBlocks).
#include <gtest/gtest.h>

#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "app/input/plain_decimal.h"
#include "app/input/text_record_parser.h"
#include "tests/support/text_rows.h"

namespace allanlab::app {
namespace {

using testing_support::ExpectSameParse;
using testing_support::ParseLog;
using testing_support::ParseText;
using testing_support::RandomNumber;
using testing_support::RandomRecord;
using testing_support::SameBits;

ParseLog Parse(const std::string& text, std::vector<std::string> columns, std::size_t chunk) {
  return ParseText(text, std::move(columns), chunk);
}

TEST(TextCommonRowTest, RowsOfEveryShapeReadAsTheGeneralParserReadsThem) {
  std::mt19937_64 rng(11);
  int failed_records = 0;
  for (int record = 0; record < 300; ++record) {
    const std::string text = RandomRecord(rng, 300, "t_s,a,b", record % 2 == 1);
    for (const std::vector<std::string>& columns :
         {std::vector<std::string>{"a"}, std::vector<std::string>{"b", "a"}, std::vector<std::string>{"b"}}) {
      const ParseLog fast = Parse(text, columns, text.size());
      const ParseLog general = Parse(text, columns, 1);
      failed_records += !general.ok;
      ExpectSameParse(fast, general, "record " + std::to_string(record) + ", " + columns.front());
      ExpectSameParse(Parse(text, columns, 61), general,
                      "chunks of 61, record " + std::to_string(record));
      ExpectSameParse(ParseText(text, columns, text.size(), {.blocks = true}), general,
                      "in blocks, record " + std::to_string(record));
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
    const ParseLog general = Parse(text, columns, 1);
    ASSERT_TRUE(general.ok) << general.error;
    ExpectSameParse(Parse(text, columns, text.size()), general, "record " + std::to_string(record));
    ExpectSameParse(ParseText(text, columns, 4096, {.blocks = true}), general,
                    "in blocks, record " + std::to_string(record));
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
