// A text read in two threads (TextRecordParser::UseTwoThreads, app/input/text_two_thread_rows.cc)
// gives what one thread gives: the same rows, values, line numbers and first error, bit for bit,
// wherever the cut of a chunk falls (on a row's line end, inside a row, inside a long line, before
// or after an error, a comment or an integer time stamp) and however the text is fed.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "app/input/text_record_parser.h"
#include "tests/support/text_rows.h"

namespace allanlab::app {
namespace {

using testing_support::ExpectSameParse;
using testing_support::ParseLog;
using testing_support::ParseText;
using testing_support::RandomRecord;

// One thread, the whole text at once: the reference.
ParseLog OneThread(const std::string& text, const std::vector<std::string>& columns,
                   std::size_t stop_after = 0) {
  return ParseText(text, columns, text.size(), {.stop_after = stop_after});
}

// Two threads from chunks of `min_bytes` on, rows one by one or in blocks.
ParseLog TwoThreads(const std::string& text, const std::vector<std::string>& columns,
                    std::size_t chunk, std::size_t min_bytes, bool blocks = false,
                    std::size_t stop_after = 0) {
  return ParseText(text, columns, chunk,
                   {.two_thread_min_bytes = min_bytes, .blocks = blocks, .stop_after = stop_after});
}

// `rows` rows "t,value" of the common shape after a header, the time in steps of 0.01.
std::string CommonRows(int rows, int first = 0) {
  std::string text;
  for (int k = first; k < first + rows; ++k) {
    text += std::to_string(k / 100) + "." + std::to_string(100 + k % 100).substr(1) + "," +
            std::to_string(k % 7) + ".25e-3\n";
  }
  return text;
}

TEST(TextTwoThreadRowsTest, RandomRecordsReadAsInOneThread) {
  std::mt19937_64 rng(21);
  std::int64_t cut_chunks = 0;
  int failed = 0;
  for (int record = 0; record < 120; ++record) {
    const bool errors = record % 2 == 1;
    // Mostly common rows, a line of another shape every ~40 or ~200 rows.
    const std::string text = RandomRecord(rng, 2000, "t_s,a,b", errors, record % 3 == 0 ? 40 : 200);
    for (const std::vector<std::string>& columns :
         {std::vector<std::string>{"a"}, std::vector<std::string>{"b", "a"}}) {
      const ParseLog one = OneThread(text, columns);
      failed += !one.ok;
      for (const std::size_t chunk : {text.size(), std::size_t{4096}, std::size_t{997}}) {
        const ParseLog two = TwoThreads(text, columns, chunk, 256, chunk == 997);
        ExpectSameParse(
            two, one, "record " + std::to_string(record) + ", chunks of " + std::to_string(chunk));
        cut_chunks += two.two_thread_chunks;
      }
    }
  }
  EXPECT_GT(cut_chunks, 1000);  // the helper had its part
  EXPECT_GT(failed, 0);         // and errors were met
}

// Chunks of every size around multiples of a row's length: the cut and the chunk's end fall on a
// line end, just before it and just after it, and a row is split between two chunks.
TEST(TextTwoThreadRowsTest, CutsAndChunkEndsAtEveryPlaceOfARow) {
  const std::string text = "t_s,rate_rad_per_s\n" + CommonRows(3000);
  const ParseLog one = OneThread(text, {""});
  ASSERT_TRUE(one.ok) << one.error;
  const std::size_t row = text.find('\n', 20) - 19;  // the first row's bytes, newline included
  for (std::size_t rows_per_chunk : {5, 64, 401}) {
    for (std::size_t extra = 0; extra < 2 * row + 2; ++extra) {
      const std::size_t chunk = 19 + rows_per_chunk * row + extra - row;
      const ParseLog two = TwoThreads(text, {""}, chunk, 64, extra % 2 == 1);
      ExpectSameParse(two, one, "chunks of " + std::to_string(chunk));
      EXPECT_GT(two.two_thread_chunks, 0);
    }
  }
}

// A line longer than the helper's part (a row whose last fields are not read; a comment), and
// one longer than 1 MiB, which is not text: the error names its line, wherever the cut falls.
TEST(TextTwoThreadRowsTest, VeryLongLines) {
  std::string text = "t_s,rate_rad_per_s,note\n" + CommonRows(20000);
  text += "200.00,1.5," + std::string(300000, 'x') + "\n";
  text += "# " + std::string(200000, 'c') + "\n";
  text += CommonRows(20000, 20001);
  for (const std::size_t chunk : {std::size_t{65536}, std::size_t{300001}, text.size()}) {
    const ParseLog one = OneThread(text, {""});
    ASSERT_TRUE(one.ok) << one.error;
    ExpectSameParse(TwoThreads(text, {""}, chunk, 4096), one,
                    "long lines, chunks of " + std::to_string(chunk));
  }
  text +=
      "400.01," + std::string(TextRecordParser::kMaxLineBytes, '1') + "\n" + CommonRows(100, 40002);
  const ParseLog one = OneThread(text, {""});
  ASSERT_FALSE(one.ok);
  EXPECT_EQ(
      one.error,
      "line 40004 is longer than 1 MiB: not a text record (raw samples? use --format f32|f64)");
  for (const std::size_t chunk : {std::size_t{1} << 20, std::size_t{3} << 19, text.size()}) {
    const ParseLog two = TwoThreads(text, {""}, chunk, 4096);
    ExpectSameParse(two, one, "an overlong line, chunks of " + std::to_string(chunk));
    EXPECT_GT(two.two_thread_chunks, 0);
  }
}

// An error in the helper's part is reported with its line; with errors in both parts, the first
// in file order is; a sink that stops in the helper's part sees the rows one thread gives it.
TEST(TextTwoThreadRowsTest, TheFirstErrorInFileOrderIsReported) {
  const std::string head = "t_s,rate_rad_per_s\n" + CommonRows(5000);
  const std::string tail = CommonRows(5000, 5001);
  const std::string bad_late = head + "50.00,1.5\n" + CommonRows(3000, 5001) + "80.01,x\n" + tail;
  const ParseLog late = OneThread(bad_late, {""});
  EXPECT_EQ(late.error, "line 8003: column rate_rad_per_s: 'x' is not a number");
  const ParseLog two_late = TwoThreads(bad_late, {""}, bad_late.size(), 1024);
  ExpectSameParse(two_late, late, "an error in the helper's part");
  EXPECT_EQ(two_late.two_thread_chunks, 1);  // the bad row in a piece of the helper's part

  const std::string bad_both = head + "50.00,y\n" + CommonRows(10, 5001) + "50.11,x\n" + tail;
  const ParseLog both = OneThread(bad_both, {""});
  EXPECT_EQ(both.error, "line 5002: column rate_rad_per_s: 'y' is not a number");
  ExpectSameParse(TwoThreads(bad_both, {""}, bad_both.size(), 1024), both, "errors in both parts");

  const std::string good = head + tail;
  for (const std::size_t stop : {std::size_t{4000}, std::size_t{7000}}) {
    const ParseLog stopped = OneThread(good, {""}, stop);
    ASSERT_EQ(stopped.rows.size(), stop);
    for (const bool blocks : {false, true}) {
      ExpectSameParse(TwoThreads(good, {""}, good.size(), 1024, blocks, stop), stopped,
                      "stopped at " + std::to_string(stop) + (blocks ? ", in blocks" : ""));
    }
  }
}

// An integer time stamp sets the origin of every time after it, so the rows the helper read
// before knowing it are read again, as one thread reads them: a stamp in this thread's part, and
// one in a piece of the helper's.
TEST(TextTwoThreadRowsTest, AnIntegerStampChangesTheRowsAfterIt) {
  for (const int stamp_row : {100, 3000}) {
    const std::string text = "t_s,rate_rad_per_s\n" + CommonRows(stamp_row) + "7,1.5\n" +
                             CommonRows(4100 - stamp_row, stamp_row + 1);
    const ParseLog one = OneThread(text, {""});
    ASSERT_TRUE(one.ok) << one.error;
    EXPECT_EQ(one.rows.back().time, 41.0 - 7);
    const ParseLog two = TwoThreads(text, {""}, text.size(), 1024);
    ExpectSameParse(two, one, "an integer stamp at row " + std::to_string(stamp_row));
    EXPECT_EQ(two.two_thread_chunks, 1);
  }
}

}  // namespace
}  // namespace allanlab::app
