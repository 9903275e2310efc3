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


// Rows as a large record's parse gives them, in chunks of `chunk` bytes.
struct LargeParse {
  bool ok = false;
  std::string error;
  std::vector<std::int64_t> lines;
  std::vector<double> values, times;
};

LargeParse ParseLarge(const std::string& text, std::size_t chunk) {
  LargeParse r;
  TextRecordParser parser("gyro_x", [&](const TextRow& row) {
    r.lines.push_back(row.line);
    r.values.push_back(row.value);
    r.times.push_back(row.time);
    return true;
  });
  r.ok = true;
  for (std::size_t i = 0; r.ok && i < text.size(); i += chunk) r.ok = parser.Feed(std::string_view(text).substr(i, chunk));
  if (r.ok) r.ok = parser.Finish();
  r.error = parser.error();
  return r;
}

// Many rows of every shape a data row takes after the first (CRLF, spaces around fields, quotes,
// trailing comments, comment and blank lines, missing values, an unread column holding text), in
// chunks that split lines anywhere: each row's value, time and line number are the ones written.
TEST(TextRecordParserTest, LargeRecordsReadTheSameInAnyChunks) {
  std::string text = "t_s,gyro_x,note\n";
  std::vector<std::int64_t> lines;
  std::vector<double> values, times;
  std::mt19937_64 engine(7);
  std::normal_distribution<double> normal;
  std::int64_t line = 1;
  for (int k = 0; k < 60000; ++k) {
    if (k % 997 == 5) {
      text += "# a comment line, 1,2\n";
      ++line;
    }
    if (k % 1499 == 9) {
      text += " \t\n";
      ++line;
    }
    const double value = 0.01 + 1e-4 * normal(engine);
    char time_text[32], value_text[40];
    std::snprintf(time_text, sizeof time_text, "%.2f", k / 100.0);
    std::snprintf(value_text, sizeof value_text, k % 3 == 0 ? "%.17g" : "%.9e", value);
    // Each row as a format: the time and the value in the same place in every shape.
    const bool missing = k % 3001 == 7;
    const char* shape = "%s,%s,x";
    if (k % 101 == 3) shape = " %s , %s ,x";
    if (k % 211 == 4) shape = "%s,\"%s\",x";
    if (k % 307 == 6) shape = "%s,%s,x # trailing comment";
    if (missing) shape = "%s,NA%.0s,x";
    char row[128];
    std::snprintf(row, sizeof row, shape, time_text, value_text);
    text.append(row);
    text.append(k % 7 == 0 ? "\r\n" : "\n");
    ++line;
    lines.push_back(line);
    values.push_back(missing ? std::nan("") : std::strtod(value_text, nullptr));
    times.push_back(std::strtod(time_text, nullptr));
  }
  for (const std::size_t chunk : {text.size(), std::size_t{1} << 16, (std::size_t{1} << 16) + 7, std::size_t{100003}, std::size_t{4093}}) {
    const LargeParse p = ParseLarge(text, chunk);
    ASSERT_TRUE(p.ok) << p.error;
    ASSERT_EQ(p.lines, lines) << "chunk " << chunk;
    ASSERT_EQ(p.times, times) << "chunk " << chunk;
    ASSERT_EQ(p.values.size(), values.size());
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (std::isnan(values[i])) {
        ASSERT_TRUE(std::isnan(p.values[i])) << "line " << lines[i];
      } else {
        ASSERT_EQ(p.values[i], values[i]) << "line " << lines[i] << ", chunk " << chunk;
      }
    }
  }
}

// A bad token, a NUL byte, a short row or a bad time deep inside a large chunk: the parse stops
// there, with the line's own number and the message of ErrorsNameTheLine.
TEST(TextRecordParserTest, AnErrorDeepInsideAChunkNamesItsLine) {
  std::string rows;
  for (int k = 0; k < 50000; ++k) rows += std::to_string(k) + "," + std::to_string(k % 13) + ".5,x\n";
  const std::string header = "t,gyro_x,note\n";
  struct Case {
    std::string bad_row, message;
  };
  const Case cases[] = {
      {"40000,1.2.3,x", "line 40002: column gyro_x: '1.2.3' is not a number"},
      {std::string("40000,1.5,\0x", 11), "line 40002 has a NUL byte: not a text record (raw samples? use --format f32|f64)"},
      {"40000", "line 40002 has 1 field(s); column gyro_x and time column t need 2"},
      {"4e4x,1", "line 40002: time column t: '4e4x' is not a number"},
  };
  for (const Case& c : cases) {
    std::string text = header;
    std::size_t at = 0;
    for (int k = 0; k < 40000; ++k) at = rows.find('\n', at) + 1;
    text += rows.substr(0, at) + c.bad_row + "\n" + rows.substr(at);
    for (const std::size_t chunk : {text.size(), std::size_t{1} << 18}) {
      const LargeParse p = ParseLarge(text, chunk);
      EXPECT_FALSE(p.ok);
      EXPECT_EQ(p.error, c.message) << "chunk " << chunk;
      EXPECT_EQ(p.lines.size(), 40000u) << c.message;  // every row before it, none after
    }
  }
}

// Integer nanosecond stamps are given relative to the first, exactly, in any chunks; when the
// first stamps are not integers, the first integer one deep inside is the origin of the rest.
TEST(TextRecordParserTest, IntegerStampsKeepTheirOriginInAnyChunks) {
  std::string text = "t_ns,gyro_x\n";
  const std::int64_t first = 1700000000123456789;
  for (int k = 0; k < 30000; ++k) text += std::to_string(first + 10000000LL * k) + "," + std::to_string(k) + "\n";
  for (const std::size_t chunk : {text.size(), std::size_t{1} << 17}) {
    const LargeParse p = ParseLarge(text, chunk);
    ASSERT_TRUE(p.ok) << p.error;
    ASSERT_EQ(p.times.size(), 30000u);
    for (int k = 0; k < 30000; ++k) ASSERT_EQ(p.times[k], 1e7 * k) << k;
  }
  // "0.5" first: no origin yet, so the first integer stamp, 1000 rows in, sets it; the times
  // after it are relative to it.
  std::string late = "t,gyro_x\n0.5,1\n";
  for (int k = 0; k < 1000; ++k) late += "0." + std::to_string(600000 + k) + ",2\n";
  late += "7,3\n";
  for (int k = 0; k < 30000; ++k) late += std::to_string(k + 8) + ".5,4\n";
  for (const std::size_t chunk : {late.size(), std::size_t{1} << 16}) {
    const LargeParse p = ParseLarge(late, chunk);
    ASSERT_TRUE(p.ok) << p.error;
    ASSERT_EQ(p.times.size(), 31002u);
    EXPECT_EQ(p.times[1000], 0.6 + 0.000999);  // no origin yet: as written
    EXPECT_EQ(p.times[1001], 0.0);             // 7: the origin
    for (int k = 0; k < 30000; ++k) ASSERT_EQ(p.times[1002 + k], k + 1.5) << k;
  }
}

}  // namespace
}  // namespace allanlab::app
