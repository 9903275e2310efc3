// The text parser alone: delimiters, header detection, comments, column choice, number rules,
// and that the chunking of the input never changes the result.
#include "app/input/text_record_parser.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace allanlab::app {
namespace {

struct Parsed {
  bool ok = false;
  std::string error;
  bool usage = false;
  std::vector<TextRow> rows;
  std::string column, time_column;
  bool header = false;
  char delimiter = 0;
};

// Feeds `text` in chunks of `chunk` bytes (0: all at once).
Parsed Parse(const std::string& text, const std::string& column = "", std::size_t chunk = 0) {
  Parsed p;
  TextRecordParser parser(column, [&](const TextRow& row) {
    p.rows.push_back(row);
    return true;
  });
  p.ok = true;
  const std::size_t step = chunk == 0 ? std::max<std::size_t>(text.size(), 1) : chunk;
  for (std::size_t i = 0; p.ok && i < text.size(); i += step) {
    p.ok = parser.Feed(std::string_view(text).substr(i, step));
  }
  if (p.ok) p.ok = parser.Finish();
  p.error = parser.error();
  p.usage = parser.error_is_usage();
  p.column = parser.value_column();
  p.time_column = parser.time_column();
  p.header = parser.has_header();
  p.delimiter = parser.delimiter();
  return p;
}

std::vector<double> Values(const Parsed& p) {
  std::vector<double> v;
  for (const TextRow& r : p.rows) v.push_back(r.value);
  return v;
}

TEST(TextRecordParserTest, CsvWithCommentsHeaderAndTimeColumn) {
  const Parsed p = Parse(
      "# recorded 2024\n\nt_s,Gyro_X,Gyro_Y\n0.00,1.5,9\n# mid comment\n"
      "0.01,-2.25,9 # trailing\n0.02,+3e-1,9\n");
  ASSERT_TRUE(p.ok) << p.error;
  EXPECT_TRUE(p.header);
  EXPECT_EQ(p.delimiter, ',');
  EXPECT_EQ(p.column, "Gyro_X");
  EXPECT_EQ(p.time_column, "t_s");
  EXPECT_EQ(Values(p), (std::vector<double>{1.5, -2.25, 0.3}));
  ASSERT_EQ(p.rows.size(), 3u);
  EXPECT_EQ(p.rows[0].line, 4);
  EXPECT_EQ(p.rows[1].line, 6);
  EXPECT_TRUE(p.rows[2].has_time);
  EXPECT_EQ(p.rows[2].time, 0.02);
}

TEST(TextRecordParserTest, TsvSemicolonAndWhitespace) {
  const Parsed tsv = Parse("time\tx\n0\t1\n1\t2\n");
  ASSERT_TRUE(tsv.ok) << tsv.error;
  EXPECT_EQ(tsv.delimiter, '\t');
  EXPECT_EQ(tsv.time_column, "time");
  EXPECT_EQ(Values(tsv), (std::vector<double>{1, 2}));
  const Parsed semi = Parse("a;b\n1;2\n3;4\n", "b");
  ASSERT_TRUE(semi.ok) << semi.error;
  EXPECT_EQ(semi.delimiter, ';');
  EXPECT_EQ(Values(semi), (std::vector<double>{2, 4}));
  const Parsed ws = Parse("  1   2\t 3\n4 5 6  \n", "2");
  ASSERT_TRUE(ws.ok) << ws.error;
  EXPECT_EQ(ws.delimiter, ' ');
  EXPECT_FALSE(ws.header);
  EXPECT_EQ(ws.column, "column 2");
  EXPECT_EQ(Values(ws), (std::vector<double>{3, 6}));
}

TEST(TextRecordParserTest, TabsThatAlignSpaceSeparatedColumnsAreWhitespace) {
  const Parsed p = Parse("  1   2\t 3\n4 5\t6\n", "2");
  ASSERT_TRUE(p.ok) << p.error;
  EXPECT_EQ(p.delimiter, ' ');
  EXPECT_FALSE(p.header);
  EXPECT_EQ(Values(p), (std::vector<double>{3, 6}));
  // Real TSV keeps its empty fields (missing values).
  const Parsed tsv = Parse("a\tb\n1\t\n2\t3\n", "b");
  ASSERT_TRUE(tsv.ok) << tsv.error;
  EXPECT_EQ(tsv.delimiter, '\t');
  EXPECT_TRUE(std::isnan(tsv.rows[0].value));
}

TEST(TextRecordParserTest, NoHeaderTakesTheFirstColumnAndHasNoTime) {
  const Parsed p = Parse("2.0,10\n1.0,20\n");
  ASSERT_TRUE(p.ok) << p.error;
  EXPECT_FALSE(p.header);
  EXPECT_EQ(p.column, "column 0");
  EXPECT_EQ(p.time_column, "");
  EXPECT_FALSE(p.rows[0].has_time);
}

// Stable32 / SigmaTheta `time value`: a headerless first column that rises is time. The decision
// waits for kTimeProbeRows rows, so the rows come out the same whatever the chunking.
TEST(TextRecordParserTest, NoHeaderIncreasingFirstColumnIsTime) {
  std::string text;
  for (int k = 0; k < 100; ++k) text += std::to_string(k) + "\t" + std::to_string(k % 3) + "\n";
  const Parsed p = Parse(text);
  ASSERT_TRUE(p.ok) << p.error;
  EXPECT_EQ(p.time_column, "column 0");
  EXPECT_EQ(p.column, "column 1");
  ASSERT_EQ(p.rows.size(), 100u);
  EXPECT_TRUE(p.rows[40].has_time);
  EXPECT_EQ(p.rows[40].time, 40);
  EXPECT_EQ(p.rows[40].value, 1);
  EXPECT_EQ(p.rows[40].line, 41);
  // Fewer rows than the probe: decided at the end.
  const Parsed few = Parse("0.5 7\n0.75 8\n");
  ASSERT_TRUE(few.ok) << few.error;
  EXPECT_EQ(few.time_column, "column 0");
  EXPECT_EQ(Values(few), (std::vector<double>{7, 8}));
  // --column 0 keeps the first column as data.
  const Parsed data = Parse(text, "0");
  ASSERT_TRUE(data.ok) << data.error;
  EXPECT_EQ(data.time_column, "");
  EXPECT_EQ(data.rows[40].value, 40);
}

TEST(TextRecordParserTest, CrLfBomQuotesAndCaseInsensitiveNames) {
  const Parsed p = Parse("\xEF\xBB\xBF\"Timestamp\",\"gyro x\"\r\n0,1\r\n1,2\r\n", "GYRO X");
  ASSERT_TRUE(p.ok) << p.error;
  EXPECT_EQ(p.time_column, "Timestamp");
  EXPECT_EQ(p.column, "gyro x");
  EXPECT_EQ(Values(p), (std::vector<double>{1, 2}));
}

TEST(TextRecordParserTest, ColumnByIndexAndTheTimeColumnItself) {
  const Parsed p = Parse("t,a,b\n0,1,2\n1,3,4\n", "2");
  ASSERT_TRUE(p.ok) << p.error;
  EXPECT_EQ(p.column, "b");
  // Choosing the time column as data: it is then just a column.
  const Parsed t = Parse("t,a\n0,1\n1,3\n", "t");
  ASSERT_TRUE(t.ok) << t.error;
  EXPECT_EQ(t.time_column, "");
  EXPECT_EQ(Values(t), (std::vector<double>{0, 1}));
}

TEST(TextRecordParserTest, MissingValuesReadAsNaNAndOverflowAsInf) {
  const Parsed p = Parse("x,y\n1,nan\n2,\n3,NA\n4,-Infinity\n5,1e999\n6,0x1p-2\n", "y");
  ASSERT_TRUE(p.ok) << p.error;
  ASSERT_EQ(p.rows.size(), 6u);
  EXPECT_TRUE(std::isnan(p.rows[0].value));
  EXPECT_TRUE(std::isnan(p.rows[1].value));
  EXPECT_TRUE(std::isnan(p.rows[2].value));
  EXPECT_EQ(p.rows[3].value, -INFINITY);
  EXPECT_EQ(p.rows[4].value, INFINITY);
  EXPECT_EQ(p.rows[5].value, 0.25);
}

TEST(TextRecordParserTest, ErrorsNameTheLine) {
  Parsed p = Parse("t,x\n0,1\n1,abc\n");
  EXPECT_FALSE(p.ok);
  EXPECT_FALSE(p.usage);
  EXPECT_EQ(p.error, "line 3: column x: 'abc' is not a number");
  p = Parse("t,x\n0,1\n1\n");
  EXPECT_FALSE(p.ok);
  EXPECT_EQ(p.error, "line 3 has 1 field(s); column x and time column t need 2");
  p = Parse("t,x\n0,1\nzz,2\n");
  EXPECT_EQ(p.error, "line 3: time column t: 'zz' is not a number");
  p = Parse("a,b\n1,2\n", "c");
  EXPECT_FALSE(p.ok);
  EXPECT_TRUE(p.usage);
  EXPECT_EQ(p.error, "--column c: no such column (a = 0, b = 1)");
  p = Parse("1,2\n", "b");
  EXPECT_TRUE(p.usage);
  EXPECT_NE(p.error.find("no header row"), std::string::npos) << p.error;
  p = Parse("1,2\n", "5");
  EXPECT_TRUE(p.usage);
  EXPECT_NE(p.error.find("has 2 column(s)"), std::string::npos) << p.error;
  p = Parse("time_s\n0\n1\n");
  EXPECT_FALSE(p.usage);
  EXPECT_EQ(p.error, "no data column besides the time column 'time_s'");
  p = Parse(std::string("1,2\n3,\0,4\n", 10));
  EXPECT_NE(p.error.find("NUL byte"), std::string::npos) << p.error;
}

TEST(TextRecordParserTest, OverlongLineIsNotText) {
  const Parsed p = Parse(std::string(TextRecordParser::kMaxLineBytes + 10, '1'), "", 4096);
  EXPECT_FALSE(p.ok);
  EXPECT_NE(p.error.find("longer than 1 MiB"), std::string::npos) << p.error;
}

TEST(TextRecordParserTest, ChunkingNeverChangesTheResult) {
  const std::string text =
      "# header follows\r\nt_s , value\r\n0, 1.25\r\n0.5,2.5 # c\r\n\r\n1.0,-3\r\n1.5,4e2";
  const Parsed whole = Parse(text);
  ASSERT_TRUE(whole.ok) << whole.error;
  EXPECT_EQ(Values(whole), (std::vector<double>{1.25, 2.5, -3, 400}));
  for (std::size_t chunk = 1; chunk < text.size(); ++chunk) {
    const Parsed p = Parse(text, "", chunk);
    ASSERT_TRUE(p.ok) << "chunk " << chunk << ": " << p.error;
    EXPECT_EQ(Values(p), Values(whole)) << "chunk " << chunk;
    ASSERT_EQ(p.rows.size(), whole.rows.size());
    for (std::size_t i = 0; i < p.rows.size(); ++i) EXPECT_EQ(p.rows[i].line, whole.rows[i].line);
  }
}

TEST(TextRecordParserTest, SinkCanStopTheParse) {
  int seen = 0;
  TextRecordParser parser("", [&](const TextRow&) { return ++seen < 2; });
  EXPECT_FALSE(parser.Feed("1\n2\n3\n"));
  EXPECT_EQ(seen, 2);
  EXPECT_EQ(parser.error(), "");
  EXPECT_FALSE(parser.Feed("4\n"));
}

TEST(ParseNumberFieldTest, Rules) {
  double v = 0;
  EXPECT_TRUE(ParseNumberField(" 1.5 ", &v));
  EXPECT_EQ(v, 1.5);
  EXPECT_TRUE(ParseNumberField("\"-2\"", &v));
  EXPECT_EQ(v, -2);
  EXPECT_TRUE(ParseNumberField(".5", &v));
  EXPECT_EQ(v, 0.5);
  EXPECT_TRUE(ParseNumberField("1e-400", &v));
  EXPECT_EQ(v, 0.0);
  EXPECT_FALSE(ParseNumberField("1,5", &v));
  EXPECT_FALSE(ParseNumberField("+-1", &v));
  EXPECT_FALSE(ParseNumberField("--1", &v));
  EXPECT_FALSE(ParseNumberField("1 2", &v));
  EXPECT_FALSE(ParseNumberField("0x", &v));
  EXPECT_FALSE(ParseNumberField("deg", &v));
}

// Every number a CSV writer prints reads as the correctly rounded double, which glibc's strtod
// (a separate implementation) gives: printf's %e, %g and %f at every precision, values across the
// double range, and strings at the edges of the plain-decimal shortcut (19 and 20 digits, 2^53
// +- 1, powers of ten 22 and 23).
TEST(ParseNumberFieldTest, AgreesWithStrtod) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> mantissa(-10.0, 10.0);
  std::uniform_int_distribution<int> exponent(-30, 30);
  std::vector<std::string> texts = {"0",   "-0.0", "1.",   "1e",  "1e+", "00012.5000", "9007199254740992",
                                    "9007199254740993", "9007199254740991.5", "1234567890123456789",
                                    "12345678901234567890", "1e22", "1e23", "4.5e-22", "4.5e-23",
                                    "0.0000000000000000000001", "1.7976931348623157e308", "5e-324",
                                    "123.456E+002", "1e0005", "+7.25"};
  char text[64];
  for (int i = 0; i < 20000; ++i) {
    const double x = mantissa(rng) * std::pow(10.0, exponent(rng));
    const int digits = i % 18;
    const char* format = i % 3 == 0 ? "%.*e" : i % 3 == 1 ? "%.*g" : "%.*f";
    std::snprintf(text, sizeof text, format, digits, x);
    texts.emplace_back(text);
  }
  for (const std::string& t : texts) {
    char* end = nullptr;
    const double expected = std::strtod(t.c_str(), &end);
    double v = 0;
    const bool parsed = ParseNumberField(t, &v);
    if (*end != '\0') {
      EXPECT_FALSE(parsed) << t;
      continue;
    }
    ASSERT_TRUE(parsed) << t;
    EXPECT_EQ(std::memcmp(&v, &expected, sizeof v), 0) << t << " read " << v << ", strtod " << expected;
  }
}

}  // namespace
}  // namespace allanlab::app
