// A raw float64 file used where it lies (MapRecordValues) against the same file read as a stream
// (ReadRecordValues): the same samples, record description and errors; files that cannot be used
// so are left to the stream. And through the command: a mapped file and the same bytes on
// standard input give the same table.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "app/input/mapped_file.h"
#include "app/input/record_reader.h"
#include "tests/support/command_test.h"

namespace allanlab::app {
namespace {

class MappedRecordTest : public testing_support::CommandTest {
 protected:
  MappedRecordTest() : CommandTest("allanlab_mapped_record_test_") {}

  std::string WriteRaw(const std::string& name, const std::vector<double>& y, std::size_t extra_bytes = 0) {
    const std::string path = (dir_ / name).string();
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(y.data()), static_cast<std::streamsize>(y.size() * sizeof(double)));
    out << std::string(extra_bytes, '\0');
    return path;
  }
  static RecordReaderOptions Options(const std::string& path) {
    RecordReaderOptions o;
    o.path = path;
    o.format = RecordFormat::kFloat64;
    o.units = "rad/s";
    o.rate_hz = 100.0;
    return o;
  }
};

std::vector<double> Rate(std::size_t n) {
  std::mt19937_64 engine(7);
  std::normal_distribution<double> normal;
  std::vector<double> y(n);
  for (double& v : y) v = 0.01 + 1e-4 * normal(engine);
  for (std::size_t k = 5000; k < 5300; ++k) y[k] = 0.5;  // a stuck stretch the reader reports
  return y;
}

// The facts a mapped read reports must be those of the streamed read of the same file.
void ExpectSameRecordInfo(const RecordInfo& a, const RecordInfo& b) {
  EXPECT_EQ(a.samples, b.samples);
  EXPECT_EQ(a.column, b.column);
  EXPECT_EQ(a.units, b.units);
  EXPECT_EQ(a.rate_source, b.rate_source);
  EXPECT_EQ(a.compression, b.compression);
  EXPECT_EQ(a.longest_constant_stretch.first, b.longest_constant_stretch.first);
  EXPECT_EQ(a.longest_constant_stretch.length, b.longest_constant_stretch.length);
}

TEST_F(MappedRecordTest, MappedAndStreamedReadsAgree) {
  const std::vector<double> y = Rate(100003);
  const std::string path = WriteRaw("r.f64", y);
  std::vector<double> read;
  RecordInfo read_info, map_info;
  RecordError read_error, map_error;
  ASSERT_TRUE(ReadRecordValues(Options(path), &read, &read_info, &read_error)) << read_error.message;
  MappedFile map;
  std::span<const double> mapped;
  std::int64_t blocks_seen = 0;
  const BlockSink count_blocks = [&](std::span<const double> block) {
    EXPECT_EQ(block.data(), mapped.data() + blocks_seen);
    blocks_seen += static_cast<std::int64_t>(block.size());
  };
  ASSERT_EQ(MapRecordValues(Options(path), &map, &mapped, &map_info, &map_error, &count_blocks), MapOutcome::kMapped);
  EXPECT_EQ(std::vector<double>(mapped.begin(), mapped.end()), read);
  EXPECT_EQ(blocks_seen, 100003);
  ExpectSameRecordInfo(map_info, read_info);
  EXPECT_EQ(map_info.longest_constant_stretch.length, 300);
}

TEST_F(MappedRecordTest, NonFiniteValuesFailAsWhenStreamed) {
  std::vector<double> y = Rate(20000);
  y[123] = std::numeric_limits<double>::quiet_NaN();
  y[19999] = std::numeric_limits<double>::infinity();
  const std::string path = WriteRaw("nan.f64", y);
  std::vector<double> read;
  RecordInfo info;
  RecordError read_error, map_error;
  EXPECT_FALSE(ReadRecordValues(Options(path), &read, &info, &read_error));
  MappedFile map;
  std::span<const double> mapped;
  EXPECT_EQ(MapRecordValues(Options(path), &map, &mapped, &info, &map_error), MapOutcome::kFailed);
  EXPECT_EQ(map_error.message, read_error.message);
  EXPECT_EQ(map_error.exit_code, read_error.exit_code);
}

// The checks left to the caller (MapRecordValuesUnchecked, made in a helper thread while the
// curve is computed) give what MapRecordValues gives: the same description once they pass, the
// same blocks to the sink, the same error when a value is not finite, and that error first when
// the file is wrong in another way too.
TEST_F(MappedRecordTest, UncheckedMappingChecksLaterAsMapRecordValues) {
  const std::string path = WriteRaw("r.f64", Rate(100003));
  RecordInfo checked_info, info;
  RecordError error;
  MappedFile checked_map, map;
  std::span<const double> checked, mapped;
  ASSERT_EQ(MapRecordValues(Options(path), &checked_map, &checked, &checked_info, &error), MapOutcome::kMapped);
  MappedRecordChecks checks;
  ASSERT_EQ(MapRecordValuesUnchecked(Options(path), &map, &mapped, &info, &error, &checks), MapOutcome::kMapped);
  EXPECT_EQ(mapped.size(), checked.size());
  std::int64_t blocks_seen = 0;
  const BlockSink count_blocks = [&](std::span<const double> block) {
    EXPECT_EQ(block.data(), mapped.data() + blocks_seen);
    blocks_seen += static_cast<std::int64_t>(block.size());
  };
  ASSERT_TRUE(checks(&count_blocks, &error)) << error.message;
  EXPECT_EQ(blocks_seen, 100003);
  ExpectSameRecordInfo(info, checked_info);

  std::vector<double> y = Rate(20000);
  y[123] = std::numeric_limits<double>::quiet_NaN();
  const std::string nan = WriteRaw("nan.f64", y);
  // The file fails the checked mapping and the unchecked one (in its checks or at once) with the
  // same message and exit code; returns that message.
  const auto fails_alike = [&](bool fails_at_once) {
    RecordError map_error, check_error;
    MappedFile checked_file, unchecked_file;
    EXPECT_EQ(MapRecordValues(Options(nan), &checked_file, &checked, &checked_info, &map_error), MapOutcome::kFailed);
    const MapOutcome outcome = MapRecordValuesUnchecked(Options(nan), &unchecked_file, &mapped, &info, &check_error, &checks);
    if (fails_at_once) {
      EXPECT_EQ(outcome, MapOutcome::kFailed);
    } else {
      EXPECT_EQ(outcome, MapOutcome::kMapped);
      EXPECT_FALSE(checks(nullptr, &check_error));
    }
    EXPECT_EQ(check_error.message, map_error.message);
    EXPECT_EQ(check_error.exit_code, map_error.exit_code);
    return check_error.message;
  };
  fails_alike(false);
  // A sidecar that miscounts the samples: the non-finite value is still what is reported.
  std::ofstream(nan + ".json") << R"({"dtype": "<f8", "num_samples": 7})";
  const std::string non_finite = fails_alike(true);
  EXPECT_NE(non_finite.find("non-finite"), std::string::npos) << non_finite;
  // Without the non-finite value, the miscount.
  y[123] = 0.01;
  WriteRaw("nan.f64", y);
  const std::string miscount = fails_alike(true);
  EXPECT_NE(miscount.find("sidecar"), std::string::npos) << miscount;
}

// Through the command: a long mapped record with a value that is not finite fails as the same
// bytes on standard input do, though its curve is computed while it is checked.
TEST_F(MappedRecordTest, NonFiniteValueFailsTheOverlappedRun) {
  std::vector<double> y = Rate(std::size_t{1} << 21);
  y[1500000] = std::numeric_limits<double>::infinity();
  WriteRaw("inf.f64", y);
  const std::string args = " --format f64 --rate 100 --units rad/s";
  const int mapped_code = Run("avar " + Path("inf.f64") + args);
  const std::string mapped = Read("err.txt");
  const int streamed_code = Run("avar -" + args + " < " + Path("inf.f64"));
  const std::string streamed = Read("err.txt");
  EXPECT_EQ(mapped_code, 1);
  EXPECT_EQ(mapped_code, streamed_code);
  EXPECT_NE(mapped.find("1500000"), std::string::npos) << mapped;
  // The message names the input: inf.f64 against stdin.
  EXPECT_EQ(mapped.substr(mapped.find("inf.f64") + 7), streamed.substr(streamed.find("stdin") + 5)) << mapped << streamed;
}

TEST_F(MappedRecordTest, OtherFilesAreLeftToTheStream) {
  const std::vector<double> y = Rate(1000);
  RecordInfo info;
  RecordError error;
  std::span<const double> mapped;
  const auto outcome = [&](const RecordReaderOptions& o) {
    MappedFile map;
    return MapRecordValues(o, &map, &mapped, &info, &error);
  };
  EXPECT_EQ(outcome(Options(WriteRaw("partial.f64", y, 3))), MapOutcome::kNotMapped);  // a partial sample
  const std::string whole = WriteRaw("whole.f64", y);
  ASSERT_EQ(std::system(("gzip -kf '" + whole + "'").c_str()), 0);
  EXPECT_EQ(outcome(Options(whole + ".gz")), MapOutcome::kNotMapped);
  EXPECT_EQ(outcome(Options("-")), MapOutcome::kNotMapped);
  RecordReaderOptions drop = Options(whole);
  drop.drop_nonfinite = true;
  EXPECT_EQ(outcome(drop), MapOutcome::kNotMapped);
  RecordReaderOptions f32 = Options(whole);
  f32.format = RecordFormat::kFloat32;
  EXPECT_EQ(outcome(f32), MapOutcome::kNotMapped);
  // A missing file is left to the stream, which names the problem.
  EXPECT_EQ(outcome(Options((dir_ / "missing.f64").string())), MapOutcome::kNotMapped);
}

TEST_F(MappedRecordTest, MappedFileAndStandardInputGiveTheSameTable) {
  // Long enough for the identification and the Allan pass to share their work with a helper.
  WriteRaw("w.f64", Rate(std::size_t{1} << 21));
  const std::string args = " --format f64 --rate 100 --units rad/s";
  const std::string degrees = " --format f64 --rate 100 --units deg/s";
  ASSERT_EQ(Run("avar " + Path("w.f64") + args), 0) << Read("err.txt");
  const std::string mapped = Read("out.txt");
  ASSERT_EQ(Run("avar -" + args + " < " + Path("w.f64")), 0) << Read("err.txt");
  const std::string streamed = Read("out.txt");
  ASSERT_EQ(Run("avar " + Path("w.f64") + degrees), 0) << Read("err.txt");  // copied and scaled
  EXPECT_NE(Read("out.txt"), mapped);
  // The first line names the input; everything else must agree.
  EXPECT_EQ(mapped.substr(mapped.find('\n')), streamed.substr(streamed.find('\n')));
}

}  // namespace
}  // namespace allanlab::app
