#include "app/reports/provenance.h"
#include "common/number_text.h"

#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

namespace allanlab::app {
namespace {

TEST(ProvenanceTest, CommentLinesStartWithHashOneFieldPerLine) {
  Provenance p = MakeProvenance("simulate", "allanlab simulate --seed 1");
  p.Add("seed", "1");
  p.Add("note", "two\nlines");
  const std::string text = ProvenanceCommentLines(p);
  std::size_t start = 0;
  int lines = 0;
  while (start < text.size()) {
    const std::size_t end = text.find('\n', start);
    ASSERT_NE(end, std::string::npos) << "unterminated last line";
    EXPECT_EQ(text[start], '#') << text.substr(start, end - start);
    start = end + 1;
    ++lines;
  }
  EXPECT_EQ(lines, 5);  // banner, date, command, seed, note
  EXPECT_NE(text.find("# seed: 1\n"), std::string::npos) << text;
  EXPECT_NE(text.find("# note: two lines\n"), std::string::npos) << text;
  EXPECT_NE(text.find("git " + p.git_sha), std::string::npos) << text;
  EXPECT_NE(text.find(p.version), std::string::npos) << text;
}

TEST(ProvenanceTest, SourceDateEpochPinsTheDate) {
  ::setenv("SOURCE_DATE_EPOCH", "86400", 1);
  const Provenance p = MakeProvenance("simulate", "");
  ::unsetenv("SOURCE_DATE_EPOCH");
  EXPECT_EQ(p.utc_date, "1970-01-02T00:00:00Z");
}

TEST(ProvenanceTest, DateIsIsoUtc) {
  const Provenance p = MakeProvenance("simulate", "");
  ASSERT_EQ(p.utc_date.size(), 20u) << p.utc_date;
  EXPECT_EQ(p.utc_date[10], 'T');
  EXPECT_EQ(p.utc_date.back(), 'Z');
}

TEST(ProvenanceTest, JsonHasFixedKeysAndFieldsInOrder) {
  Provenance p = MakeProvenance("simulate", "allanlab simulate");
  p.Add("seed", "42");
  const nlohmann::ordered_json j = ProvenanceJson(p);
  EXPECT_EQ(j.at("command"), "simulate");
  EXPECT_EQ(j.at("git_sha"), p.git_sha);
  EXPECT_EQ(j.at("command_line"), "allanlab simulate");
  EXPECT_EQ(j.at("seed"), "42");
  EXPECT_EQ(j.begin().key(), "command");
}

TEST(ProvenanceTest, CommandLineIsQuotedOnlyWhereNeeded) {
  const char* argv[] = {"allanlab", "simulate",    "--units", "deg/h",
                        "-o",       "my file.csv", "it's",    ""};
  EXPECT_EQ(QuotedCommandLine(8, argv),
            "allanlab simulate --units deg/h -o 'my file.csv' 'it'\\''s' ''");
}

TEST(ProvenanceTest, ShortestDecimalRoundTrips) {
  EXPECT_EQ(ShortestDecimal(0.1), "0.1");
  EXPECT_EQ(ShortestDecimal(200.0), "200");
  const double third = 1.0 / 3.0;
  EXPECT_EQ(std::strtod(ShortestDecimal(third).c_str(), nullptr), third);
}

}  // namespace
}  // namespace allanlab::app
