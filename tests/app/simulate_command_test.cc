// End-to-end tests of `allanlab simulate`: the built binary is run in a fresh directory per test.
#include <stdlib.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "app/reports/allan_plot.h"
#include "sim/sensor_spec.h"
#include "tests/support/read_file.h"

namespace allanlab::app {
namespace {

namespace fs = std::filesystem;

// 100 Hz, first-order band-limit at 20 Hz from a 4 x 100 Hz chain (internal Nyquist 200 Hz).
constexpr const char* kSpec = R"(name: app_test_gyro
description: "gyro for the simulate command tests"
sample_rate: 100 Hz
terms:
  - {type: arw, N: 0.1 deg/sqrt(h)}
  - {type: bias_instability, B: 1 deg/h}
  - {type: rrw, K: 0.5 deg/h/sqrt(h)}
band_limit: {type: first_order, cutoff: 20 Hz, oversampling: 4, sampling: point}
)";

// The same with fc = 500 Hz above the internal Nyquist frequency: the loader must refuse it.
constexpr const char* kBadSpec = R"(name: app_test_bad_gyro
description: "band-limit above the internal Nyquist frequency"
sample_rate: 100 Hz
terms:
  - {type: arw, N: 0.1 deg/sqrt(h)}
band_limit: {type: first_order, cutoff: 500 Hz, oversampling: 4, sampling: point}
)";

using testing_support::ReadAll;

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream is(text);
  for (std::string line; std::getline(is, line);) lines.push_back(line);
  return lines;
}

std::string Quote(const std::string& s) { return "'" + s + "'"; }

struct RunResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

struct CsvRecord {
  std::vector<std::string> comments;  // '#' lines, without the '#'
  std::string header;
  std::vector<std::string> rows;
  std::string Comment(const std::string& key) const {
    for (const std::string& c : comments) {
      if (c.rfind(" " + key + ": ", 0) == 0) return c.substr(key.size() + 3);
    }
    return "";
  }
};

CsvRecord ParseCsv(const std::string& text) {
  CsvRecord csv;
  bool header_seen = false;
  for (const std::string& line : Lines(text)) {
    if (!header_seen && !line.empty() && line[0] == '#') {
      csv.comments.push_back(line.substr(1));
    } else if (!header_seen) {
      csv.header = line;
      header_seen = true;
    } else {
      csv.rows.push_back(line);
    }
  }
  return csv;
}

std::vector<double> Column(const CsvRecord& csv, int column) {
  std::vector<double> values;
  for (const std::string& row : csv.rows) {
    const char* p = row.c_str();
    for (int c = 0; c < column; ++c) p = std::strchr(p, ',') + 1;
    values.push_back(std::strtod(p, nullptr));
  }
  return values;
}

class SimulateCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string templ = (fs::path(::testing::TempDir()) / "simulate_test.XXXXXX").string();
    ASSERT_NE(::mkdtemp(templ.data()), nullptr);
    dir_ = templ;
    std::ofstream(dir_ / "gyro.yaml") << kSpec;
    std::ofstream(dir_ / "bad_gyro.yaml") << kBadSpec;
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string Path(const std::string& name) const { return (dir_ / name).string(); }

  // Runs `allanlab <args>` in the test's directory (so relative paths stay in it) with `env`
  // (e.g. "PATH=/x") in front.
  RunResult Run(const std::string& args, const std::string& env = "") const {
    const std::string command = "cd " + Quote(dir_.string()) + " && " + env + " " +
                                Quote(ALLANLAB_BINARY) + " " + args + " >" +
                                Quote(Path("stdout.txt")) + " 2>" + Quote(Path("stderr.txt"));
    const int status = std::system(command.c_str());
    RunResult r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = ReadAll(Path("stdout.txt"));
    r.err = ReadAll(Path("stderr.txt"));
    fs::remove(Path("stdout.txt"));
    fs::remove(Path("stderr.txt"));
    return r;
  }

  // `simulate` on the test spec, 100 Hz, writing `out`.
  RunResult Simulate(const std::string& extra, const std::string& out = "out.csv") const {
    return Run("simulate --sensor " + Quote(Path("gyro.yaml")) + " -o " + Quote(Path(out)) + " " +
               extra);
  }

  std::vector<std::string> Entries() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) names.push_back(e.path().filename());
    std::sort(names.begin(), names.end());
    return names;
  }

  fs::path dir_;
};

std::string AnyPreset() {
  const std::vector<std::string> names = sim::PresetNames();
  if (std::find(names.begin(), names.end(), "mg25_mems") != names.end()) return "mg25_mems";
  return names.empty() ? "" : names.front();
}

TEST_F(SimulateCommandTest, CsvHasProvenanceThenHeaderThenOneRowPerSample) {
  const RunResult r = Simulate("--duration 2 --seed 7");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  const CsvRecord csv = ParseCsv(ReadAll(Path("out.csv")));
  ASSERT_FALSE(csv.comments.empty());
  EXPECT_NE(csv.comments[0].find("allanlab simulate"), std::string::npos) << csv.comments[0];
  EXPECT_NE(csv.comments[0].find("git "), std::string::npos) << csv.comments[0];
  EXPECT_NE(csv.Comment("date"), "");
  EXPECT_NE(csv.Comment("command").find("--seed 7"), std::string::npos);
  EXPECT_EQ(csv.Comment("sensor_spec"), Path("gyro.yaml"));
  EXPECT_EQ(csv.Comment("sensor_name"), "app_test_gyro");
  EXPECT_EQ(csv.Comment("seed"), "7");
  EXPECT_EQ(csv.Comment("trial"), "0");
  EXPECT_EQ(csv.Comment("sample_rate"), "100 Hz (spec)");
  EXPECT_EQ(csv.Comment("duration"), "2 s");
  EXPECT_EQ(csv.Comment("samples"), "200");
  EXPECT_EQ(csv.Comment("units"), "deg/s");
  EXPECT_EQ(csv.header, "time_s,rate_deg_per_s");
  ASSERT_EQ(csv.rows.size(), 200u);
  const std::vector<double> time = Column(csv, 0);
  EXPECT_EQ(time[0], 0.0);
  EXPECT_EQ(time[1], 0.01);
  EXPECT_EQ(time[199], 1.99);
  for (double rate : Column(csv, 1)) ASSERT_TRUE(std::isfinite(rate));
}

TEST_F(SimulateCommandTest, PresetUsesItsOwnSampleRate) {
  const std::string preset = AnyPreset();
  ASSERT_FALSE(preset.empty()) << "no shipped presets";
  const RunResult r =
      Run("simulate --preset " + preset + " --duration 0.5 --seed 1 -o " + Quote(Path("out.csv")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const CsvRecord csv = ParseCsv(ReadAll(Path("out.csv")));
  EXPECT_EQ(csv.Comment("preset"), preset);
  EXPECT_NE(csv.Comment("sample_rate").find("(spec)"), std::string::npos);
  EXPECT_EQ(std::to_string(csv.rows.size()), csv.Comment("samples"));
}

TEST_F(SimulateCommandTest, RateOverridesTheSpec) {
  const RunResult r = Simulate("--rate 50 --duration 2 --seed 7");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const CsvRecord csv = ParseCsv(ReadAll(Path("out.csv")));
  EXPECT_EQ(csv.Comment("sample_rate"), "50 Hz (--rate)");
  ASSERT_EQ(csv.rows.size(), 100u);
  EXPECT_EQ(Column(csv, 0)[1], 0.02);
}

TEST_F(SimulateCommandTest, SameSeedAndTrialGiveIdenticalDataRows) {
  ASSERT_EQ(Simulate("--duration 5 --seed 11", "a.csv").exit_code, 0);
  ASSERT_EQ(Simulate("--duration 5 --seed 11", "b.csv").exit_code, 0);
  ASSERT_EQ(Simulate("--duration 5 --seed 12", "c.csv").exit_code, 0);
  ASSERT_EQ(Simulate("--duration 5 --seed 11 --trial 1", "d.csv").exit_code, 0);
  const CsvRecord a = ParseCsv(ReadAll(Path("a.csv")));
  const CsvRecord b = ParseCsv(ReadAll(Path("b.csv")));
  EXPECT_EQ(a.header, b.header);
  EXPECT_TRUE(a.rows == b.rows) << "same seed, different records";
  EXPECT_FALSE(a.rows == ParseCsv(ReadAll(Path("c.csv"))).rows) << "seed ignored";
  EXPECT_FALSE(a.rows == ParseCsv(ReadAll(Path("d.csv"))).rows) << "trial ignored";
}

TEST_F(SimulateCommandTest, PinnedDateMakesTheWholeFileReproducible) {
  const std::string args = "simulate --sensor gyro.yaml -o out.csv --duration 1 --seed 3";
  ASSERT_EQ(Run(args, "SOURCE_DATE_EPOCH=0").exit_code, 0);
  const std::string first = ReadAll(Path("out.csv"));
  ASSERT_EQ(Run(args, "SOURCE_DATE_EPOCH=0").exit_code, 0);
  EXPECT_EQ(ReadAll(Path("out.csv")), first);
  EXPECT_NE(first.find("# date: 1970-01-01T00:00:00Z\n"), std::string::npos);
}

TEST_F(SimulateCommandTest, UnitsScaleTheRecord) {
  ASSERT_EQ(Simulate("--duration 1 --seed 5 --units deg/s", "s.csv").exit_code, 0);
  ASSERT_EQ(Simulate("--duration 1 --seed 5 --units deg/h", "h.csv").exit_code, 0);
  ASSERT_EQ(Simulate("--duration 1 --seed 5 --units rad/s", "r.csv").exit_code, 0);
  const CsvRecord s = ParseCsv(ReadAll(Path("s.csv")));
  const CsvRecord h = ParseCsv(ReadAll(Path("h.csv")));
  const CsvRecord r = ParseCsv(ReadAll(Path("r.csv")));
  EXPECT_EQ(h.header, "time_s,rate_deg_per_h");
  EXPECT_EQ(r.header, "time_s,rate_rad_per_s");
  EXPECT_EQ(h.Comment("units"), "deg/h");
  const std::vector<double> deg_s = Column(s, 1), deg_h = Column(h, 1), rad_s = Column(r, 1);
  ASSERT_EQ(deg_s.size(), 100u);
  for (std::size_t k = 0; k < deg_s.size(); ++k) {
    EXPECT_NEAR(deg_h[k], 3600.0 * deg_s[k], 1e-12 * std::abs(deg_h[k]));
    EXPECT_NEAR(rad_s[k], deg_s[k] * M_PI / 180.0, 1e-12 * std::abs(rad_s[k]));
  }
}

TEST_F(SimulateCommandTest, Float64IsEightBytesPerSampleWithAJsonSidecar) {
  ASSERT_EQ(Simulate("--duration 3 --seed 9", "ref.csv").exit_code, 0);
  const RunResult r = Simulate("--duration 3 --seed 9 --format f64", "out.f64");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string raw = ReadAll(Path("out.f64"));
  ASSERT_EQ(raw.size(), 8u * 300u);
  const nlohmann::json sidecar = nlohmann::json::parse(ReadAll(Path("out.f64.json")));
  EXPECT_EQ(sidecar.at("data").at("num_samples"), 300);
  EXPECT_EQ(sidecar.at("data").at("sample_rate_hz"), 100.0);
  EXPECT_EQ(sidecar.at("data").at("units"), "deg/s");
  EXPECT_EQ(sidecar.at("data").at("dtype"), "<f8");
  EXPECT_EQ(sidecar.at("provenance").at("seed"), "9");
  EXPECT_FALSE(sidecar.at("provenance").at("git_sha").get<std::string>().empty());
  // An output named *.f64 is raw float64 without --format: the same bytes.
  ASSERT_EQ(Simulate("--duration 3 --seed 9", "named.f64").exit_code, 0);
  EXPECT_EQ(ReadAll(Path("named.f64")), raw);
  EXPECT_TRUE(fs::exists(Path("named.f64.json")));
  // The CSV prints shortest round-trip decimals, so both formats hold the same doubles.
  const std::vector<double> csv = Column(ParseCsv(ReadAll(Path("ref.csv"))), 1);
  for (std::size_t k = 0; k < csv.size(); ++k) {
    unsigned char bytes[8];
    std::memcpy(bytes, raw.data() + 8 * k, 8);
    std::uint64_t bits = 0;
    for (int b = 7; b >= 0; --b) bits = (bits << 8) | bytes[b];  // little-endian
    double value;
    std::memcpy(&value, &bits, 8);
    ASSERT_EQ(value, csv[k]) << "sample " << k;
  }
}

TEST_F(SimulateCommandTest, AvarTableHasOctaveRowsUpToNOver8) {
  const RunResult r =
      Simulate("--duration 20.48 --seed 4 --avar-table " + Quote(Path("table.csv")));  // N = 2048
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const CsvRecord table = ParseCsv(ReadAll(Path("table.csv")));
  EXPECT_EQ(table.Comment("seed"), "4");
  EXPECT_EQ(table.header,
            "m,tau_s,oavar_sim,oavar_exact,oavar_ieee,adev_sim_deg_per_h,adev_exact_deg_per_h");
  ASSERT_EQ(table.rows.size(), 9u);  // m = 1 .. 256 = N/8
  const std::vector<double> m = Column(table, 0), tau = Column(table, 1),
                            oavar_sim = Column(table, 2), oavar_exact = Column(table, 3),
                            oavar_ieee = Column(table, 4), adev_sim = Column(table, 5);
  for (std::size_t i = 0; i < m.size(); ++i) {
    EXPECT_EQ(m[i], std::ldexp(1.0, static_cast<int>(i)));
    EXPECT_DOUBLE_EQ(tau[i], m[i] / 100.0);
    EXPECT_GT(oavar_sim[i], 0.0);
    EXPECT_GT(oavar_exact[i], 0.0);
    EXPECT_GT(oavar_ieee[i], 0.0);
    EXPECT_NEAR(adev_sim[i], std::sqrt(oavar_sim[i]) * 180.0 / M_PI * 3600.0, 1e-9 * adev_sim[i]);
    // A loose sanity band only; the statistics are tested in tests/sim.
    EXPECT_LT(oavar_sim[i], 20 * oavar_exact[i]);
    EXPECT_GT(oavar_sim[i], oavar_exact[i] / 20);
  }
}

TEST_F(SimulateCommandTest, PlotWritesAPng) {
  std::string why;
  if (!FindGnuplot(&why)) GTEST_SKIP() << why;
  const RunResult r = Simulate("--duration 60 --seed 4 --plot " + Quote(Path("plot.png")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string png = ReadAll(Path("plot.png"));
  ASSERT_GT(png.size(), 1000u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
}

TEST_F(SimulateCommandTest, HelpExplainsOptionsWithUnits) {
  const RunResult r = Run("simulate --help");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* word : {"--preset", "--sensor", "--rate", "Hz", "--duration", "seconds",
                           "--seed", "--trial", "--format", "f64", "--units", "deg/s", "deg/h",
                           "rad/s", "--plot", "--avar-table", "(rad/s)^2"}) {
    EXPECT_NE(r.out.find(word), std::string::npos) << "help lacks " << word << ":\n" << r.out;
  }
  const std::string preset = AnyPreset();
  if (!preset.empty()) {
    EXPECT_NE(r.out.find(preset), std::string::npos) << "presets not listed";
  }
}

TEST_F(SimulateCommandTest, NoSubcommandIsAUsageError) {
  const RunResult r = Run("");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err.rfind("allanlab: error: ", 0), 0u) << r.err;
}

TEST_F(SimulateCommandTest, MistypedSubcommandIsNamed) {
  const RunResult r = Run("simulat --duration 1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err,
            "allanlab: error: unknown command 'simulat' (known: simulate, avar, fit, diagnose, diagnosis-benchmark, sweep, validate; see allanlab --help)\n");
}

// A run that must fail: its exit code, a word its message must contain, and the arguments, in
// which {spec}, {bad_spec}, {preset} and {dir} are replaced. Every case writes -o {dir}/out.csv
// unless its arguments say otherwise; that file exists beforehand and must survive.
struct BadCase {
  std::string name;
  int exit_code;
  std::string message_word;
  std::string args;
  std::string env = "";
};

std::ostream& operator<<(std::ostream& os, const BadCase& c) { return os << c.name; }

class SimulateBadInputTest : public SimulateCommandTest,
                             public ::testing::WithParamInterface<BadCase> {};

std::string Substitute(std::string text, const std::string& key, const std::string& value) {
  for (std::size_t at; (at = text.find(key)) != std::string::npos;)
    text.replace(at, key.size(), value);
  return text;
}

TEST_P(SimulateBadInputTest, FailsWithOneLineAndLeavesFilesAlone) {
  const BadCase& c = GetParam();
  std::ofstream(Path("out.csv")) << "precious\n";
  fs::create_directory(Path("empty_bin"));
  const std::vector<std::string> before = Entries();
  std::string args = c.args;
  if (args.find(" -o ") == std::string::npos) args += " -o {dir}/out.csv";
  args = Substitute(args, "{bad_spec}", Quote(Path("bad_gyro.yaml")));
  args = Substitute(args, "{spec}", Quote(Path("gyro.yaml")));
  args = Substitute(args, "{preset}", AnyPreset());
  args = Substitute(args, "{dir}", dir_.string());
  const std::string env = Substitute(c.env, "{dir}", dir_.string());

  const RunResult r = Run("simulate " + args, env);
  EXPECT_EQ(r.exit_code, c.exit_code) << args << "\n" << r.err;
  EXPECT_EQ(r.err.rfind("allanlab simulate: error: ", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(c.message_word), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(ReadAll(Path("out.csv")), "precious\n");
  EXPECT_EQ(Entries(), before) << "a file was created or removed";
}

INSTANTIATE_TEST_SUITE_P(
    AllErrors, SimulateBadInputTest,
    ::testing::Values(
        BadCase{"UnknownPreset", 2, "no_such_gyro", "--preset no_such_gyro --duration 10 --seed 1"},
        BadCase{"PresetAndSensor", 2, "exactly one",
                "--preset {preset} --sensor {spec} --duration 10 --seed 1"},
        BadCase{"NeitherPresetNorSensor", 2, "exactly one", "--duration 10 --seed 1"},
        BadCase{"NegativeRate", 2, "--rate", "--sensor {spec} --rate -5 --duration 10 --seed 1"},
        BadCase{"ZeroRate", 2, "--rate", "--sensor {spec} --rate 0 --duration 10 --seed 1"},
        BadCase{"NanRate", 2, "--rate", "--sensor {spec} --rate nan --duration 10 --seed 1"},
        BadCase{"InfiniteRate", 2, "--rate", "--sensor {spec} --rate inf --duration 10 --seed 1"},
        BadCase{"TextRate", 2, "--rate", "--sensor {spec} --rate fast --duration 10 --seed 1"},
        BadCase{"NegativeDuration", 2, "--duration", "--sensor {spec} --duration -10 --seed 1"},
        BadCase{"ZeroDuration", 2, "--duration", "--sensor {spec} --duration 0 --seed 1"},
        BadCase{"NanDuration", 2, "--duration", "--sensor {spec} --duration nan --seed 1"},
        BadCase{"HugeDuration", 2, "--duration", "--sensor {spec} --duration 1e300 --seed 1"},
        BadCase{"FewerThan16Samples", 2, "16", "--sensor {spec} --duration 0.15 --seed 1"},
        BadCase{"MissingDuration", 2, "--duration", "--sensor {spec} --seed 1"},
        BadCase{"MissingSeed", 2, "--seed", "--sensor {spec} --duration 10"},
        BadCase{"NegativeSeed", 2, "--seed", "--sensor {spec} --duration 10 --seed -1"},
        BadCase{"TextSeed", 2, "--seed", "--sensor {spec} --duration 10 --seed abc"},
        BadCase{"UnknownUnits", 2, "deg/min",
                "--sensor {spec} --duration 10 --seed 1 --units deg/min"},
        BadCase{"UnknownFormat", 2, "f32", "--sensor {spec} --duration 10 --seed 1 --format f32"},
        BadCase{"CsvFormatForAnF64Name", 2, "contradicts",
                "--sensor {spec} --duration 10 --seed 1 --format csv -o {dir}/new.f64"},
        BadCase{"F64FormatForACsvName", 2, "contradicts",
                "--sensor {spec} --duration 10 --seed 1 --format f64 -o {dir}/new.csv"},
        BadCase{"UnknownOption", 2, "--frobnicate",
                "--sensor {spec} --duration 10 --seed 1 --frobnicate"},
        BadCase{"CutoffAboveInternalNyquist", 1, "Nyquist",
                "--sensor {bad_spec} --duration 10 --seed 1"},
        BadCase{"RateMovesNyquistBelowCutoff", 2, "--rate",
                "--sensor {spec} --rate 5 --duration 10 --seed 1"},
        BadCase{"MissingSpecFile", 1, "no_such.yaml",
                "--sensor {dir}/no_such.yaml --duration 10 --seed 1"},
        BadCase{"OutputDirectoryMissing", 1, "no_such_dir",
                "--sensor {spec} --duration 10 --seed 1 -o {dir}/no_such_dir/out.csv"},
        BadCase{"OutputIsADirectory", 1, "directory",
                "--sensor {spec} --duration 10 --seed 1 -o {dir}/empty_bin"},
        BadCase{"TableUnwritableKeepsRecord", 1, "no_such_dir",
                "--sensor {spec} --duration 10 --seed 1 --avar-table {dir}/no_such_dir/t.csv"},
        BadCase{"PlotUnwritableKeepsRecord", 1, "no_such_dir",
                "--sensor {spec} --duration 10 --seed 1 --plot {dir}/no_such_dir/p.png"},
        BadCase{"SamePathTwice", 2, "--avar-table",
                "--sensor {spec} --duration 10 --seed 1 --avar-table {dir}/out.csv"},
        BadCase{"SameRelativePathTwice", 2, "--plot",
                "--sensor {spec} --duration 10 --seed 1 -o new.csv --plot ./new.csv"},
        BadCase{"GnuplotMissing", 1, "gnuplot",
                "--sensor {spec} --duration 10 --seed 1 --plot {dir}/p.png",
                "PATH={dir}/empty_bin"}),
    [](const ::testing::TestParamInfo<BadCase>& info) { return info.param.name; });

}  // namespace
}  // namespace allanlab::app
