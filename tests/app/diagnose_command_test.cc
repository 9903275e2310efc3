// End-to-end tests of `allanlab diagnose`: the JSON output (stable keys) on a
// simulated record, and clear refusals. The built binary runs in a fresh directory per test.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "sim/band_limit.h"
#include "sim/sensor_model.h"
#include "sim/white_rate_noise.h"
#include "tests/support/command_test.h"
#include "tests/support/read_file.h"

namespace allanlab::app {
namespace {

namespace fs = std::filesystem;

class DiagnoseCommandTest : public testing_support::CommandTest {
 protected:
  DiagnoseCommandTest() : CommandTest("allanlab_diagnose", "diagnose") {}
  void WriteRecord(const std::string& name, std::int64_t n) {
    sim::SensorModel model;
    model.sample_clock = SampleClock::FromRateHz(100.0);
    sim::WhiteRateNoise white;
    white.arw_rad_per_sqrt_s = 1e-4;
    model.terms = {white};
    std::ofstream out(dir_ / name);
    out << "rate_rad_per_s\n";
    for (double v : model.Generate(5, 0, n)) out << v << "\n";
  }
};

TEST_F(DiagnoseCommandTest, WritesTheJsonContract) {
  WriteRecord("rec.csv", 4096);
  std::ostringstream args;
  args << Path("rec.csv") << " --units rad/s --rate 100 --trials 5 --json " << Path("d.json")
       << " --report " << Path("d.md");
  ASSERT_EQ(Run(args.str()), 0) << Read("err.txt");
  const auto j = nlohmann::json::parse(Read("d.json"));
  ASSERT_TRUE(j.contains("gap"));
  EXPECT_TRUE(j["gap"]["significant"].is_boolean());
  EXPECT_TRUE(j["gap"]["regions"].is_array());
  EXPECT_TRUE(j["verdict"]["effect"].is_string());
  EXPECT_TRUE(j["verdict"]["params"].is_object());
  EXPECT_TRUE(j["verdict"]["also_consistent"].is_array());
  EXPECT_TRUE(j["candidates"].is_array());
  EXPECT_TRUE(j["baseline"]["coefficients"].contains("N"));
  EXPECT_TRUE(j["provenance"].is_object());
  EXPECT_EQ(j["gap"]["significant"].get<bool>(), j["verdict"]["effect"] != "none");
  EXPECT_NE(Read("d.md").find("verdict"), std::string::npos);
}

// The report says where the baseline's band-limit comes from: the user's sensor model (--sensor)
// or the fit (the default); the JSON's baseline.source says which baseline it is.
TEST_F(DiagnoseCommandTest, SaysWhoseBandLimitTheBaselineHolds) {
  const std::string spec =
      "name: test\nsample_rate: 100 Hz\nterms:\n  - {type: arw, N: 0.3 deg/sqrt(h)}\n"
      "band_limit: {type: butterworth2, cutoff: 20 Hz, oversampling: 8, sampling: average}\n";
  std::ofstream(dir_ / "spec.yaml") << spec;
  sim::SensorModel model;
  model.sample_clock = SampleClock::FromRateHz(100.0);
  model.terms = {sim::WhiteRateNoise{.arw_rad_per_sqrt_s = 0.3 * M_PI / 180.0 / 60.0}};
  model.band_limit = {sim::LowPassKind::kButterworth2, 20.0, 8, sim::OutputSampling::kAverage};
  {
    std::ofstream out(dir_ / "rec.csv");
    out << "rate_rad_per_s\n";
    for (double v : model.Generate(5, 0, 8192)) out << v << "\n";
  }
  std::ostringstream given;
  given << Path("rec.csv") << " --rate 100 --trials 5 --sensor " << Path("spec.yaml") << " --json " << Path("s.json");
  ASSERT_EQ(Run(given.str()), 0) << Read("err.txt");
  EXPECT_NE(Read("out.txt").find("the baseline includes your sensor model's band-limit: a second-order Butterworth "
                                 "low-pass at 20 Hz"),
            std::string::npos)
      << Read("out.txt");
  EXPECT_EQ(nlohmann::json::parse(Read("s.json"))["baseline"]["source"], "sensor");
  // The user's own filter near Nyquist is not a finding to dismiss.
  std::ofstream(dir_ / "near_nyquist.yaml") << "name: test\nsample_rate: 100 Hz\nterms:\n"
                                               "  - {type: arw, N: 0.3 deg/sqrt(h)}\n"
                                               "band_limit: {type: butterworth2, cutoff: 48 Hz, "
                                               "oversampling: 8, sampling: average}\n";
  std::ostringstream near_nyquist;
  near_nyquist << Path("rec.csv") << " --rate 100 --trials 5 --sensor " << Path("near_nyquist.yaml");
  ASSERT_EQ(Run(near_nyquist.str()), 0) << Read("err.txt");
  EXPECT_NE(Read("out.txt").find("your sensor model's band-limit: a second-order Butterworth low-pass at 48 Hz"),
            std::string::npos)
      << Read("out.txt");
  EXPECT_EQ(Read("out.txt").find("not a finding"), std::string::npos) << Read("out.txt");
  std::ostringstream fitted;
  fitted << Path("rec.csv") << " --rate 100 --trials 5 --json " << Path("f.json");
  ASSERT_EQ(Run(fitted.str()), 0) << Read("err.txt");
  EXPECT_EQ(Read("out.txt").find("your sensor model"), std::string::npos) << Read("out.txt");
  EXPECT_EQ(nlohmann::json::parse(Read("f.json"))["baseline"]["source"], "fit");
}

// stderr is a file here: no progress unless asked; with --progress one line per stage on stderr
// and none in the JSON or on stdout; --progress with --quiet is refused.
TEST_F(DiagnoseCommandTest, ProgressOnStderrOnlyWhenAskedOffATerminal) {
  WriteRecord("rec.csv", 4096);
  std::ostringstream args;
  args << Path("rec.csv") << " --units rad/s --rate 100 --trials 5 --json " << Path("d.json");
  ASSERT_EQ(Run(args.str()), 0) << Read("err.txt");
  EXPECT_EQ(Read("err.txt").find("diagnose rec.csv:"), std::string::npos) << Read("err.txt");
  ASSERT_EQ(Run(args.str() + " --progress"), 0) << Read("err.txt");
  const std::string err = Read("err.txt");
  EXPECT_NE(err.find("diagnose rec.csv: baseline, "), std::string::npos) << err;
  EXPECT_NE(err.find("diagnose rec.csv: views, "), std::string::npos) << err;
  EXPECT_EQ(err.find('\r'), std::string::npos) << err;
  EXPECT_EQ(Read("out.txt").find("diagnose rec.csv:"), std::string::npos);
  EXPECT_EQ(Read("d.json").find("diagnose rec.csv:"), std::string::npos);
  EXPECT_EQ(Run(args.str() + " --progress --quiet"), 2);
  EXPECT_NE(Read("err.txt").find("--quiet excludes --progress"), std::string::npos) << Read("err.txt");
}

TEST_F(DiagnoseCommandTest, RefusesTooShortRecordsAndMissingInput) {
  WriteRecord("short.csv", 100);
  std::string args = Path("short.csv");
  args += " --units rad/s --rate 100";
  EXPECT_EQ(Run(args), 1);
  const std::string err = Read("err.txt");
  EXPECT_NE(err.find("allanlab diagnose: error:"), std::string::npos) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_EQ(Run("--trials 5"), 2);
  std::string curve = "--curve ";
  curve += Path("short.csv");
  EXPECT_EQ(Run(curve), 2);  // no --record-length / --rate
}

// Robustness: a stuck stretch is named (stderr and the JSON notes), not silently
// blamed on an effect; a NaN is refused with its line, or dropped with --drop-nonfinite.
TEST_F(DiagnoseCommandTest, NamesStuckStretchesAndRefusesNaN) {
  WriteRecord("rec.csv", 8192);
  std::vector<std::string> lines;
  {
    std::ifstream in(dir_ / "rec.csv");
    for (std::string line; std::getline(in, line);) lines.push_back(line);
  }
  auto write = [&](const std::string& name, const std::vector<std::string>& rows) {
    std::ofstream out(dir_ / name);
    for (const auto& r : rows) out << r << "\n";
  };
  std::vector<std::string> stuck = lines;
  for (int k = 3001; k <= 3500; ++k) stuck[k] = "0.00125";  // 500 samples, 5 s
  write("stuck.csv", stuck);
  std::string args = Path("stuck.csv");
  args += " --units rad/s --rate 100 --trials 0 --json " + Path("s.json");
  ASSERT_EQ(Run(args), 0) << Read("err.txt");
  EXPECT_NE(Read("err.txt").find("500 identical samples in a row (5 s from sample 3000"), std::string::npos)
      << Read("err.txt");
  const auto j = nlohmann::json::parse(Read("s.json"));
  bool noted = false;
  for (const auto& n : j["notes"]) noted |= n.get<std::string>().find("identical samples") != std::string::npos;
  EXPECT_TRUE(noted) << j["notes"];

  std::vector<std::string> with_nan = lines;
  with_nan[200] = "nan";
  write("nan.csv", with_nan);
  args = Path("nan.csv");
  args += " --units rad/s --rate 100 --trials 0";
  EXPECT_EQ(Run(args), 1);
  EXPECT_NE(Read("err.txt").find("line(s) 201"), std::string::npos) << Read("err.txt");
  EXPECT_EQ(Run(args + " --drop-nonfinite"), 0) << Read("err.txt");
  EXPECT_NE(Read("err.txt").find("dropped 1 non-finite"), std::string::npos) << Read("err.txt");
}

}  // namespace
}  // namespace allanlab::app
