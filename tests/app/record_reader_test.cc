// The record reader: every container (text, f32, f64; plain, gzip, xz), the sample rate from a
// time column or --rate, irregular steps, and every bad input with its message and exit code.
#include "app/input/record_reader.h"

#include <gtest/gtest.h>
#include <omp.h>
#include <stdlib.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <limits>
#include <vector>

#include "app/input/byte_source.h"
#include "app/commands/subcommand.h"

namespace allanlab::app {
namespace {

namespace fs = std::filesystem;

class RecordReaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string templ = (fs::path(::testing::TempDir()) / "record_reader_test.XXXXXX").string();
    ASSERT_NE(::mkdtemp(templ.data()), nullptr);
    dir_ = templ;
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string Write(const std::string& name, const std::string& bytes) const {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }
  // Compresses `path` with the system tool ("xz" or "gzip"), keeping the original.
  std::string Compress(const std::string& path, const std::string& tool) const {
    const std::string command = tool + " -kf '" + path + "'";
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
    return path + (tool == "xz" ? ".xz" : ".gz");
  }

  struct Result {
    bool ok = false;
    std::vector<double> values;
    RecordInfo info;
    RecordError error;
  };
  static Result Read(RecordReaderOptions options) {
    Result r;
    r.ok = ReadRecordValues(options, &r.values, &r.info, &r.error);
    return r;
  }
  static RecordReaderOptions Options(const std::string& path) {
    RecordReaderOptions o;
    o.path = path;
    o.units = "rad/s";  // the files here do not state their units (see StatedUnits tests)
    return o;
  }

  fs::path dir_;
};

std::string Csv(int n, double rate_hz) {
  std::string text = "# a comment line\nt_s,gyro_x,gyro_y\n";
  for (int k = 0; k < n; ++k) {
    char line[96];
    std::snprintf(line, sizeof line, "%.6f,%.17g,%d\n", k / rate_hz, std::sin(0.1 * k), k);
    text += line;
  }
  return text;
}

TEST_F(RecordReaderTest, PlainGzipAndXzGiveTheSameValues) {
  const std::string plain = Write("r.csv", Csv(5000, 100));
  const Result a = Read(Options(plain));
  ASSERT_TRUE(a.ok) << a.error.message;
  EXPECT_EQ(a.info.compression, Compression::kNone);
  EXPECT_EQ(a.values.size(), 5000u);
  EXPECT_EQ(a.values[7], std::sin(0.1 * 7));
  EXPECT_EQ(a.info.column, "gyro_x");
  EXPECT_EQ(a.info.time_column, "t_s");
  EXPECT_TRUE(a.info.has_header);
  EXPECT_EQ(a.info.sample_clock.rate_hz(), 100);  // rounded to 10 digits, not 99.99999999999993
  EXPECT_EQ(a.info.rate_source, "time column t_s");
  EXPECT_EQ(a.info.time.irregular_steps, 0);
  EXPECT_EQ(a.info.lines, 5002);
  for (const std::string tool : {"gzip", "xz"}) {
    const Result c = Read(Options(Compress(plain, tool)));
    ASSERT_TRUE(c.ok) << tool << ": " << c.error.message;
    EXPECT_EQ(CompressionName(c.info.compression), tool == "gzip" ? "gzip" : "xz");
    EXPECT_EQ(c.values, a.values) << tool;
  }
}

TEST_F(RecordReaderTest, ConcatenatedGzipMembersAndXzStreamsReadAsOne) {
  const std::string a = Compress(Write("a.csv", "1\n2\n"), "gzip");
  const std::string b = Compress(Write("b.csv", "3\n4\n"), "gzip");
  std::ifstream ia(a, std::ios::binary), ib(b, std::ios::binary);
  std::string both((std::istreambuf_iterator<char>(ia)), {});
  both.append((std::istreambuf_iterator<char>(ib)), {});
  RecordReaderOptions o = Options(Write("ab.gz", both));
  o.rate_hz = 1;
  Result r = Read(o);
  ASSERT_TRUE(r.ok) << r.error.message;
  EXPECT_EQ(r.values, (std::vector<double>{1, 2, 3, 4}));

  const std::string xa = Compress(Write("c.csv", "5\n6\n"), "xz");
  const std::string xb = Compress(Write("d.csv", "7\n"), "xz");
  std::ifstream ja(xa, std::ios::binary), jb(xb, std::ios::binary);
  std::string xboth((std::istreambuf_iterator<char>(ja)), {});
  xboth.append((std::istreambuf_iterator<char>(jb)), {});
  o.path = Write("cd.xz", xboth);
  r = Read(o);
  ASSERT_TRUE(r.ok) << r.error.message;
  EXPECT_EQ(r.values, (std::vector<double>{5, 6, 7}));
}

TEST_F(RecordReaderTest, CompressionIsFoundByContentNotName) {
  const std::string gz = Compress(Write("x.csv", "1\n2\n3\n"), "gzip");
  fs::rename(gz, dir_ / "looks_plain.csv");
  RecordReaderOptions o = Options((dir_ / "looks_plain.csv").string());
  o.rate_hz = 2;
  const Result r = Read(o);
  ASSERT_TRUE(r.ok) << r.error.message;
  EXPECT_EQ(r.info.compression, Compression::kGzip);
  EXPECT_EQ(r.values, (std::vector<double>{1, 2, 3}));
}

TEST_F(RecordReaderTest, RawFloat32AndFloat64LittleEndian) {
  std::string f32, f64;
  std::vector<double> expected;
  for (int k = 0; k < 1001; ++k) {
    const double v = std::cos(0.3 * k) * 1e-3;
    const auto b32 = std::bit_cast<std::uint32_t>(static_cast<float>(v));
    const auto b64 = std::bit_cast<std::uint64_t>(v);
    for (int i = 0; i < 4; ++i) f32 += static_cast<char>((b32 >> (8 * i)) & 0xff);
    for (int i = 0; i < 8; ++i) f64 += static_cast<char>((b64 >> (8 * i)) & 0xff);
    expected.push_back(v);
  }
  RecordReaderOptions o = Options(Write("r.f64", f64));
  o.format = RecordFormat::kFloat64;
  o.rate_hz = 200;
  Result r = Read(o);
  ASSERT_TRUE(r.ok) << r.error.message;
  EXPECT_EQ(r.values, expected);
  EXPECT_EQ(r.info.sample_clock.rate_hz(), 200);
  EXPECT_EQ(r.info.rate_source, "--rate");
  EXPECT_EQ(r.info.column, "float64 samples");

  o.path = Compress(Write("r.f32", f32), "xz");
  o.format = RecordFormat::kFloat32;
  r = Read(o);
  ASSERT_TRUE(r.ok) << r.error.message;
  ASSERT_EQ(r.values.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(r.values[i], static_cast<double>(static_cast<float>(expected[i])));
  }
}

TEST_F(RecordReaderTest, RateFromTimeColumnAndAgreeingRate) {
  RecordReaderOptions o = Options(Write("r.csv", Csv(100, 50)));
  o.rate_hz = 50.02;  // within 1e-3 relative: used as given
  Result r = Read(o);
  ASSERT_TRUE(r.ok) << r.error.message;
  EXPECT_EQ(r.info.sample_clock.rate_hz(), 50.02);
  EXPECT_EQ(r.info.rate_source, "--rate (time column t_s agrees)");
  o.rate_hz = 50.1;
  r = Read(o);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.error.exit_code, kExitUsageError);
  EXPECT_EQ(r.error.message,
            o.path +
                ": --rate 50.1 Hz disagrees with the time column t_s (50 Hz from its step "
                "of 0.02 s); drop --rate or fix it");
}

TEST_F(RecordReaderTest, IrregularStepsAreReported) {
  const Result r =
      Read(Options(Write("r.csv", "time,x\n0,1\n1,2\n2,3\n5,4\n6,5\n7,6\n7.5,7\n8.5,8\n")));
  ASSERT_TRUE(r.ok) << r.error.message;
  EXPECT_EQ(r.info.sample_clock.rate_hz(), 1.0);
  EXPECT_EQ(r.info.time.irregular_steps, 2);
  EXPECT_EQ(r.info.time.largest_step_s, 3.0);
  EXPECT_EQ(r.info.time.largest_step_line, 5);
  EXPECT_EQ(r.info.time.smallest_step_s, 0.5);
  EXPECT_EQ(r.info.time.smallest_step_line, 8);
}

TEST_F(RecordReaderTest, NonFiniteValuesAreListedOrDroppedExplicitly) {
  std::string text = "t,x\n";
  for (int k = 0; k < 20; ++k) {
    text += std::to_string(k) + "," + (k % 3 == 1 ? std::string("nan") : std::to_string(k)) + "\n";
  }
  RecordReaderOptions o = Options(Write("r.csv", text));
  Result r = Read(o);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.error.exit_code, kExitRuntimeError);
  EXPECT_EQ(r.error.message,
            o.path +
                ": 7 non-finite value(s) (NaN, inf or missing) in column x at line(s) 3, 6, "
                "9, 12, 15, ...; remove them or pass --drop-nonfinite to skip them");
  o.drop_nonfinite = true;
  r = Read(o);
  ASSERT_TRUE(r.ok) << r.error.message;
  EXPECT_EQ(r.info.dropped_nonfinite, 7);
  EXPECT_EQ(r.values.size(), 13u);
  EXPECT_EQ(r.values[1], 2.0);
  // A dropped row leaves a hole in time, which is reported like any gap.
  EXPECT_EQ(r.info.time.irregular_steps, 6);
  EXPECT_EQ(r.info.time.largest_step_s, 2.0);

  std::string raw(8 * 4, '\0');
  const auto nan_bits = std::bit_cast<std::uint64_t>(std::numeric_limits<double>::infinity());
  for (int i = 0; i < 8; ++i) raw[8 + i] = static_cast<char>((nan_bits >> (8 * i)) & 0xff);
  RecordReaderOptions b = Options(Write("r.f64", raw));
  b.format = RecordFormat::kFloat64;
  b.rate_hz = 1;
  r = Read(b);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.error.message,
            b.path +
                ": 1 non-finite value(s) (NaN, inf or missing) in the samples at 0-based "
                "index(es) 1; remove them or pass --drop-nonfinite to skip them");
}

TEST_F(RecordReaderTest, BadInputs) {
  struct Case {
    std::string name;
    std::string content;  // empty: the file is not created
    std::string column;
    bool rate;
    int code;
    std::string message;  // after "<path>: " unless it starts with "cannot"
  };
  const std::vector<Case> cases = {
      {"missing.csv", "", "", true, kExitRuntimeError,
       "cannot open {path}: No such file or directory"},
      {"empty.csv", "# only a comment\n\n", "", true, kExitRuntimeError,
       "no data rows (2 line(s) of comments, blank lines or header)"},
      {"header_only.csv", "t,x\n", "", false, kExitRuntimeError,
       "no data rows (1 line(s) of comments, blank lines or header)"},
      {"text.csv", "t,x\n0,1\n1,one\n", "", false, kExitRuntimeError,
       "line 3: column x: 'one' is not a number"},
      {"two.csv", "t,x\n0,1\n1,2\n", "", false, kExitRuntimeError,
       "only 2 sample(s) in x; at least 3 are needed"},
      {"backwards.csv", "t,x\n0,1\n1,2\n0.5,3\n", "", false, kExitRuntimeError,
       "time is not increasing: line 4 has t = 0.5 s after t = 1 s at line 3 (sort the record "
       "first)"},
      {"norate.csv", "a,b\n0,1\n1,2\n2,3\n", "", false, kExitUsageError,
       "no time column (t, t_s, time, time_s, timestamp, or with a unit: t_ms, time_us, "
       "timestamp_ns, %time ...) in the header: give the sample rate "
       "with --rate HZ"},
      {"nohead.csv", "1,1\n0,2\n2,3\n", "", false, kExitUsageError,
       "no time column (t, t_s, time, time_s, timestamp, or with a unit: t_ms, time_us, "
       "timestamp_ns, %time ...) in the file (it has no header row, and its first column does "
       "not increase): give the sample rate with --rate HZ"},
      {"column.csv", "t,x\n0,1\n", "y", false, kExitUsageError,
       "--column y: no such column (t = 0, x = 1)"},
      {"binary.csv", std::string("\x01\x00\x7f\x03\n", 5), "", true, kExitRuntimeError,
       "line 1 has a NUL byte: not a text record (raw samples? use --format f32|f64)"},
      {"bad.xz",
       std::string("\xfd"
                   "7zXZ\x00garbage-garbage-garbage",
                   28),
       "", true, kExitRuntimeError, "{path}: corrupt xz data"},
  };
  for (const Case& c : cases) {
    RecordReaderOptions o =
        Options(c.content.empty() && c.name == "missing.csv" ? (dir_ / c.name).string()
                                                             : Write(c.name, c.content));
    o.column = c.column;
    if (c.rate) o.rate_hz = 1;
    const Result r = Read(o);
    EXPECT_FALSE(r.ok) << c.name;
    EXPECT_EQ(r.error.exit_code, c.code) << c.name;
    std::string expected = c.message;
    const bool absolute = expected.find("{path}") != std::string::npos;
    if (absolute) {
      expected.replace(expected.find("{path}"), 6, o.path);
    } else {
      expected = o.path + ": " + expected;
    }
    EXPECT_EQ(r.error.message, expected) << c.name;
  }
}

TEST_F(RecordReaderTest, TruncatedCompressedFilesFail) {
  const std::string text = Csv(20000, 100);
  for (const std::string tool : {"gzip", "xz"}) {
    const std::string path = Compress(Write("t_" + tool + ".csv", text), tool);
    const auto size = fs::file_size(path);
    fs::resize_file(path, size / 2);
    const Result r = Read(Options(path));
    EXPECT_FALSE(r.ok) << tool;
    EXPECT_EQ(r.error.exit_code, kExitRuntimeError) << tool;
    EXPECT_NE(r.error.message.find("truncated " + std::string(tool == "gzip" ? "gzip" : "xz")),
              std::string::npos)
        << r.error.message;
  }
}

// A raw float64 record of many read chunks: read straight into the chunk's doubles, the values
// are the file's to the bit; a non-finite sample deep inside is named; a partial last sample fails.
TEST_F(RecordReaderTest, LongRawFloat64RecordsReadWholeChunks) {
  std::vector<double> expected;
  std::string f64;
  for (int k = 0; k < 100003; ++k) {
    const double v = std::sin(0.001 * k) + 1e-9 * k;
    expected.push_back(v);
    const auto bits = std::bit_cast<std::uint64_t>(v);
    for (int i = 0; i < 8; ++i) f64 += static_cast<char>((bits >> (8 * i)) & 0xff);
  }
  RecordReaderOptions o = Options(Write("long.f64", f64));
  o.format = RecordFormat::kFloat64;
  o.rate_hz = 100;
  Result r = Read(o);
  ASSERT_TRUE(r.ok) << r.error.message;
  EXPECT_EQ(r.values, expected);
  EXPECT_EQ(r.info.samples, 100003);

  std::string with_nan = f64;
  const auto nan_bits = std::bit_cast<std::uint64_t>(std::numeric_limits<double>::quiet_NaN());
  for (int i = 0; i < 8; ++i) with_nan[8 * 70001 + i] = static_cast<char>((nan_bits >> (8 * i)) & 0xff);
  o.path = Write("nan.f64", with_nan);
  r = Read(o);
  EXPECT_EQ(r.error.exit_code, kExitRuntimeError);
  EXPECT_NE(r.error.message.find("70001"), std::string::npos) << r.error.message;

  o.path = Write("cut.f64", f64 + std::string(3, '\0'));
  r = Read(o);
  EXPECT_EQ(r.error.exit_code, kExitRuntimeError);
  EXPECT_EQ(r.error.message, o.path + ": the data ends 3 byte(s) into a 8-byte sample: truncated "
                                      "file, or not float64 data");
}

TEST_F(RecordReaderTest, RawWithoutRateOrWithAPartialSampleFails) {
  RecordReaderOptions o = Options(Write("r.f32", std::string(10, '\0')));
  o.format = RecordFormat::kFloat32;
  Result r = Read(o);
  EXPECT_EQ(r.error.exit_code, kExitUsageError);
  EXPECT_EQ(r.error.message, o.path + ": raw f32 samples carry no time and no sidecar " + o.path +
                                 ".json gives their rate: give the sample rate with --rate HZ");
  o.rate_hz = 10;
  o.units.clear();
  r = Read(o);
  EXPECT_EQ(r.error.exit_code, kExitUsageError);
  EXPECT_EQ(r.error.message, o.path + ": raw f32 samples state no units and no sidecar " + o.path +
                                 ".json gives them: give --units deg/s, deg/h or rad/s");
  o.units = "rad/s";
  r = Read(o);
  EXPECT_EQ(r.error.exit_code, kExitRuntimeError);
  EXPECT_EQ(r.error.message, o.path +
                                 ": the data ends 2 byte(s) into a 4-byte sample: truncated "
                                 "file, or not float32 data");
}

TEST_F(RecordReaderTest, ParseRecordFormat) {
  RecordFormat f;
  std::string why;
  EXPECT_TRUE(ParseRecordFormat("f32", &f, &why));
  EXPECT_EQ(f, RecordFormat::kFloat32);
  EXPECT_FALSE(ParseRecordFormat("csv", &f, &why));
  EXPECT_EQ(why, "unknown format 'csv' (expected text, f32 or f64)");
}

}  // namespace
}  // namespace allanlab::app

namespace allanlab::app {
namespace {

// A `rostopic echo -p` style record: '%time' in integer nanoseconds since the epoch (19 digits,
// beyond a double's 53 bits), then the rate column.
std::string RosCsv(const std::string& time_name, int n, std::int64_t step_ns) {
  std::string text = time_name + ",field.angular_velocity.x\n";
  const std::int64_t start_ns = 1700000000123456789;
  for (int k = 0; k < n; ++k) {
    text += std::to_string(start_ns + k * step_ns) + "," + std::to_string(0.001 * (k % 7)) + "\n";
  }
  return text;
}

TEST_F(RecordReaderTest, NanosecondTimeColumnsGiveTheExactRate) {
  const Result r = Read(Options(Write("ros.csv", RosCsv("%time", 2000, 10'000'000))));
  ASSERT_TRUE(r.ok) << r.error.message;
  EXPECT_EQ(r.info.sample_clock.rate_hz(), 100.0);
  EXPECT_EQ(r.info.time_unit_s, 1e-9);
  EXPECT_EQ(r.info.time.irregular_steps, 0);
  EXPECT_EQ(r.info.rate_source, "time column %time in ns");

  const Result ms = Read(Options(Write("ms.csv", RosCsv("t_ms", 100, 5))));
  ASSERT_TRUE(ms.ok) << ms.error.message;
  EXPECT_EQ(ms.info.sample_clock.rate_hz(), 200.0);
}

TEST_F(RecordReaderTest, BareTimeColumnInNanosecondsIsRejectedUnlessTheUnitIsGiven) {
  const std::string path = Write("bare.csv", RosCsv("timestamp", 500, 2'500'000));
  const Result bare = Read(Options(path));
  EXPECT_FALSE(bare.ok);
  EXPECT_EQ(bare.error.exit_code, kExitUsageError);
  EXPECT_NE(bare.error.message.find("--time-units"), std::string::npos) << bare.error.message;

  RecordReaderOptions o = Options(path);
  o.time_unit_s = 1e-9;
  const Result told = Read(o);
  ASSERT_TRUE(told.ok) << told.error.message;
  EXPECT_EQ(told.info.sample_clock.rate_hz(), 400.0);
}

// The units: what the file states meets --units; nothing stated and nothing given is refused.
TEST_F(RecordReaderTest, UnitsComeFromTheFileAndMustAgreeWithUnitsOption) {
  const std::string simulated = Write("sim.csv",
                                      "# allanlab simulate 0.1.0\n# units: rad/s\n"
                                      "time_s,rate_rad_per_s\n0,0.001\n0.01,0.002\n0.02,0.003\n");
  RecordReaderOptions o = Options(simulated);
  o.units.clear();
  Result r = Read(o);
  ASSERT_TRUE(r.ok) << r.error.message;
  EXPECT_EQ(r.info.units, "rad/s");
  EXPECT_EQ(r.info.units_source, "column rate_rad_per_s");
  o.units = "deg/s";
  r = Read(o);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.error.exit_code, kExitUsageError);
  EXPECT_EQ(r.error.message, simulated + ": --units (deg/s) contradicts column rate_rad_per_s "
                                         "(rad/s): drop --units or correct it");

  // The '# units:' line alone, and against the column name.
  o = Options(Write("line.csv", "# units: deg/h\nt,w\n0,1\n1,2\n2,3\n"));
  o.units.clear();
  r = Read(o);
  ASSERT_TRUE(r.ok) << r.error.message;
  EXPECT_EQ(r.info.units, "deg/h");
  EXPECT_EQ(r.info.units_source, "the '# units: deg/h' line");
  o = Options(Write("both.csv", "# units: deg/s\nt,w_rad_s\n0,1\n1,2\n2,3\n"));
  o.units.clear();
  r = Read(o);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.error.message, o.path + ": the '# units: deg/s' line (deg/s) contradicts column "
                                      "w_rad_s (rad/s)");
  // A '# units:' line that is not a rate unit is an error about the file.
  o = Options(Write("accel.csv", "# units: g\nt,a\n0,1\n1,2\n2,3\n"));
  r = Read(o);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.error.exit_code, kExitRuntimeError);
  EXPECT_EQ(r.error.message, o.path + ": the '# units:' line: unknown rate unit 'g' (expected "
                                      "deg/s, deg/h or rad/s)");

  // Stated nowhere: refused, with how to state them.
  o = Options(Write("bare.csv", "t_s,Gyro_X\n0,1\n0.01,2\n0.02,3\n"));
  o.units.clear();
  r = Read(o);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.error.exit_code, kExitUsageError);
  EXPECT_EQ(r.error.message, o.path + ": the units of column Gyro_X are not stated in the file (a "
                                      "unit in the column name such as _dps or _rad_s, or a "
                                      "'# units:' line): give --units deg/s, deg/h or rad/s");
}

TEST_F(RecordReaderTest, RawRecordsReadTheirSidecar) {
  std::string f64;
  for (int k = 0; k < 1000; ++k) {
    const double v = 0.5 * k;
    f64.append(reinterpret_cast<const char*>(&v), 8);  // little-endian host (x86, arm64)
  }
  const std::string path = Write("r.f64", f64);
  Write("r.f64.json", R"({"provenance": {}, "data": {"dtype": "<f8", "num_samples": 1000,
                          "sample_rate_hz": 250, "units": "deg/s"}})");
  RecordReaderOptions o = Options(path);
  o.format = RecordFormat::kFloat64;
  o.units.clear();
  Result r = Read(o);
  ASSERT_TRUE(r.ok) << r.error.message;
  EXPECT_EQ(r.info.sample_clock.rate_hz(), 250);
  EXPECT_EQ(r.info.rate_source, "the sidecar " + path + ".json");
  EXPECT_EQ(r.info.units, "deg/s");
  EXPECT_EQ(r.info.units_source, "the sidecar " + path + ".json");
  // The compressed record finds the same sidecar.
  o.path = Compress(path, "xz");
  r = Read(o);
  ASSERT_TRUE(r.ok) << r.error.message;
  EXPECT_EQ(r.info.units_source, "the sidecar " + path + ".json");
  o.path = path;

  o.units = "rad/s";
  r = Read(o);
  EXPECT_EQ(r.error.exit_code, kExitUsageError);
  EXPECT_EQ(r.error.message, path + ": --units (rad/s) contradicts the sidecar " + path +
                                 ".json (deg/s): drop --units or correct it");
  o.units.clear();
  o.rate_hz = 100;
  r = Read(o);
  EXPECT_EQ(r.error.exit_code, kExitUsageError);
  EXPECT_EQ(r.error.message, path + ": --rate 100 Hz disagrees with the sidecar " + path +
                                 ".json (250 Hz); drop --rate or fix it");
  o.rate_hz.reset();
  o.format = RecordFormat::kFloat32;
  r = Read(o);
  EXPECT_EQ(r.error.exit_code, kExitUsageError);
  EXPECT_EQ(r.error.message, path + ": the sidecar " + path +
                                 ".json says dtype <f8, not <f4 as --format f32 reads: fix "
                                 "--format");
  // A record cut short no longer matches its sidecar's count.
  o.format = RecordFormat::kFloat64;
  Write("r.f64", f64.substr(0, 800));
  r = Read(o);
  EXPECT_EQ(r.error.exit_code, kExitRuntimeError);
  EXPECT_EQ(r.error.message, path + ": 100 samples, but the sidecar " + path +
                                 ".json says 1000: a truncated file or another record's sidecar");
  Write("r.f64.json", "{not json");
  r = Read(o);
  EXPECT_EQ(r.error.exit_code, kExitRuntimeError);
  EXPECT_EQ(r.error.message, path + ": the sidecar " + path + ".json is not a JSON object");
}

// The Stable32 / SigmaTheta layout: no header, `time value` columns.
TEST_F(RecordReaderTest, HeaderlessIncreasingFirstColumnIsTime) {
  std::string text;
  for (int k = 0; k < 200; ++k) {
    // A gap of one missing sample at k = 100.
    const double t = 0.005 * (k < 100 ? k : k + 1);
    text += std::to_string(t) + " " + std::to_string(std::sin(0.3 * k)) + "\n";
  }
  RecordReaderOptions o = Options(Write("two.txt", text));
  Result r = Read(o);
  ASSERT_TRUE(r.ok) << r.error.message;
  EXPECT_EQ(r.info.time_column, "column 0");
  EXPECT_TRUE(r.info.time_column_guessed);
  EXPECT_EQ(r.info.column, "column 1");
  EXPECT_EQ(r.info.sample_clock.rate_hz(), 200);
  EXPECT_EQ(r.info.time.irregular_steps, 1);
  ASSERT_EQ(r.values.size(), 200u);
  EXPECT_EQ(r.values[3], std::stod(std::to_string(std::sin(0.9))));
  // --column 1 (the old way to read this layout) reads the same, and an agreeing --rate is fine.
  o.column = "1";
  o.rate_hz = 200;
  r = Read(o);
  ASSERT_TRUE(r.ok) << r.error.message;
  EXPECT_EQ(r.info.rate_source, "--rate (time column 0 agrees)");
  // A --rate that disagrees wins over a guess (the column may be a sample counter).
  o.rate_hz = 1000;
  r = Read(o);
  ASSERT_TRUE(r.ok) << r.error.message;
  EXPECT_EQ(r.info.sample_clock.rate_hz(), 1000);
  EXPECT_TRUE(r.info.time_column.empty());
  EXPECT_EQ(r.info.rate_source,
            "--rate (the headerless first column, read as time, gives 200 Hz: not used)");
  // --column 0 reads the first column as data.
  o.column = "0";
  r = Read(o);
  ASSERT_TRUE(r.ok) << r.error.message;
  EXPECT_TRUE(r.info.time_column.empty());
  EXPECT_EQ(r.values[1], 0.005);
  // A first column that does not rise is data, as before.
  o = Options(Write("noisy.txt", "0.3 1\n0.1 2\n0.2 3\n"));
  o.rate_hz = 1;
  r = Read(o);
  ASSERT_TRUE(r.ok) << r.error.message;
  EXPECT_TRUE(r.info.time_column.empty());
  EXPECT_EQ(r.values, (std::vector<double>{0.3, 0.1, 0.2}));
}

// A text longer than a two-thread chunk (TextRecordParser::kTwoThreadMinBytes), read in two threads
// where there are two cores, gives what one thread gives (OMP_NUM_THREADS=1): the values, counts,
// time steps and messages, with the line numbers of rows in the helper's part of a chunk.
TEST_F(RecordReaderTest, LargeTextReadsInTwoThreadsAsInOne) {
  const auto text = [](int bad_row, const std::string& bad, const char* newline = "\n") {
    std::string t = "t_s,rate_rad_per_s\n";
    char row[64];
    for (int k = 0; k < 300000; ++k) {
      std::snprintf(row, sizeof row, "%.2f,%.9e%s", k / 100.0, 0.01 + 1e-4 * std::sin(k), newline);
      t += k == bad_row ? bad : row;
    }
    return t;
  };
  const std::string cases[][2] = {{"clean", text(-1, "")},
                                  {"nan", text(250000, "2500.00,nan\n")},
                                  {"gap", text(230001, "")},
                                  {"back", text(270001, "2600.00,0.01\n")},
                                  {"bad", text(260000, "2600.00,0.01x\n")},
                                  {"crlf", "# units: rad/s\r\n" + text(-1, "", "\r\n")}};
  for (const auto& [name, bytes] : cases) {
    const RecordReaderOptions o = Options(Write(name + ".csv", bytes));
    const Result two = Read(o);
    const int threads = omp_get_max_threads();
    omp_set_num_threads(1);
    const Result one = Read(o);
    omp_set_num_threads(threads);
    EXPECT_EQ(two.ok, one.ok) << name;
    EXPECT_EQ(two.error.message, one.error.message) << name;
    EXPECT_EQ(two.error.exit_code, one.error.exit_code) << name;
    EXPECT_TRUE(two.values == one.values) << name;
    EXPECT_EQ(two.info.lines, one.info.lines) << name;
    EXPECT_EQ(two.info.samples, one.info.samples) << name;
    EXPECT_EQ(two.info.time.irregular_steps, one.info.time.irregular_steps) << name;
    EXPECT_EQ(two.info.time.largest_step_line, one.info.time.largest_step_line) << name;
    EXPECT_EQ(two.info.time.smallest_step_line, one.info.time.smallest_step_line) << name;
    EXPECT_EQ(two.info.longest_constant_stretch.length, one.info.longest_constant_stretch.length)
        << name;
  }
  EXPECT_EQ(Read(Options(dir_ / "nan.csv")).error.message,
            (dir_ / "nan.csv").string() +
                ": 1 non-finite value(s) (NaN, inf or missing) in column rate_rad_per_s at "
                "line(s) 250002; remove them or pass --drop-nonfinite to skip them");
  EXPECT_EQ(Read(Options(dir_ / "bad.csv")).error.message,
            (dir_ / "bad.csv").string() +
                ": line 260002: column rate_rad_per_s: '0.01x' is not a number");
  EXPECT_EQ(Read(Options(dir_ / "back.csv")).error.message,
            (dir_ / "back.csv").string() +
                ": time is not increasing: line 270003 has t = 2600 s after t = 2700 s at line "
                "270002 (sort the record first)");
  const Result gap = Read(Options(dir_ / "gap.csv"));
  EXPECT_EQ(gap.info.time.largest_step_line, 230003);
  const Result clean = Read(Options(dir_ / "clean.csv"));
  ASSERT_EQ(clean.values.size(), 300000u);
  for (int k = 0; k < 300000; k += 997) {
    char value[32];
    std::snprintf(value, sizeof value, "%.9e", 0.01 + 1e-4 * std::sin(k));
    ASSERT_EQ(clean.values[static_cast<std::size_t>(k)], std::strtod(value, nullptr)) << k;
  }
}

}  // namespace
}  // namespace allanlab::app
