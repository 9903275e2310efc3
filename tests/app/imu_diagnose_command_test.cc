// `allanlab diagnose --imu / --columns`: a diagnosis per column, gyro and accelerometer axes alike,
// each in its sensor's units; one JSON with a section per column.
#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/wait.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <string>

#include "tests/support/read_file.h"

namespace allanlab::app {
namespace {

namespace fs = std::filesystem;
using testing_support::ReadAll;

std::string Quote(const std::string& s) { return "'" + s + "'"; }

constexpr double kRateHz = 100.0;
constexpr int kSamples = 60000;
constexpr double kGravity = 9.80665;     // m/s^2 per g (the data-sheet g)
constexpr double kAccelSigmaG = 0.002;   // white accelerometer noise, 2 mg
constexpr double kStepG = 0.003;         // a 3 mg bias step ...
constexpr double kStepTimeS = 300.0;     // ... halfway through

class ImuDiagnoseCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string templ = (fs::path(::testing::TempDir()) / "imu_diagnose_command_test.XXXXXX").string();
    ASSERT_NE(::mkdtemp(templ.data()), nullptr);
    dir_ = templ;
    // Written here, not by sim/: Gaussian white noise from the standard library, the step added by hand.
    std::mt19937_64 engine(5);
    std::normal_distribution<double> normal;
    std::ofstream csv(dir_ / "imu.csv");
    csv.precision(17);
    csv << "t_s,Gyro_X,Accel_X_g,Accel_Y_g\n";
    for (int k = 0; k < kSamples; ++k) {
      const double t = k / kRateHz;
      csv << t << "," << 0.05 * normal(engine) << ","
          << 1.0 + kAccelSigmaG * normal(engine) + (t >= kStepTimeS ? kStepG : 0.0) << ","
          << kAccelSigmaG * normal(engine) << "\n";
    }
  }
  void TearDown() override { fs::remove_all(dir_); }

  int Run(const std::string& args) const {
    const std::string command = "cd " + Quote(dir_.string()) + " && " + Quote(ALLANLAB_BINARY) +
                                " diagnose imu.csv " + args + " >out.txt 2>err.txt";
    const int status = std::system(command.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  std::string Read(const std::string& name) const { return ReadAll((dir_ / name).string()); }

  fs::path dir_;
};

TEST_F(ImuDiagnoseCommandTest, EveryAxisInItsSensorsUnits) {
  // A false-alarm rate of 1e-3 (not the default 0.05): the test is about units, and a chance
  // departure on any of the three axes would change a verdict it checks.
  ASSERT_EQ(Run("--imu --units deg/s --trials 3 --false-alarm 0.001 --json d.json"), 0) << Read("err.txt");
  const std::string out = Read("out.txt");
  EXPECT_NE(out.find("# column Gyro_X (gyro, deg/s)\nin plain words:"), std::string::npos) << out;
  EXPECT_NE(out.find("# column Accel_X_g (accelerometer, g)\naccelerometer: Q velocity quantization, N velocity "
                     "random walk (VRW)"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("the acceleration level rises at t = "), std::string::npos) << out;
  const nlohmann::json j = nlohmann::json::parse(Read("d.json"));
  ASSERT_EQ(j["columns"].size(), 3u);
  EXPECT_EQ(j["columns"][0]["sensor"], "gyro");
  EXPECT_EQ(j["columns"][0]["baseline"]["coefficients"]["N"]["unit"], "deg/sqrt(h)");

  // The stepped axis: a bias step, its size the difference of two half-record means of white
  // noise (sd 2 sigma / sqrt(n) = 0.016 mg); 5 sd allowed, in m/s^2 (JSON) and mg / g (summary).
  const nlohmann::json& x = j["columns"][1];
  EXPECT_EQ(x["column"], "Accel_X_g");
  EXPECT_EQ(x["sensor"], "accelerometer");
  EXPECT_EQ(x["units"], "g");
  ASSERT_EQ(x["verdict"]["effect"], "bias_step") << x["verdict"];
  const double sd_g = 2.0 * kAccelSigmaG / std::sqrt(kSamples);
  const nlohmann::json& params = x["verdict"]["params"];
  ASSERT_TRUE(params.contains("size_m_per_s2")) << params;
  EXPECT_FALSE(params.contains("size_rad_per_s")) << params;
  EXPECT_NEAR(params["size_m_per_s2"].get<double>(), kStepG * kGravity, 5 * sd_g * kGravity);
  EXPECT_NEAR(params["time_s"].get<double>(), kStepTimeS, 5.0);
  const nlohmann::json& size = x["summary"]["effects"][0]["quantities"][0];
  EXPECT_EQ(size["unit"], "mg");
  EXPECT_NEAR(size["value"].get<double>(), 1e3 * kStepG, 1e3 * 5 * sd_g);
  EXPECT_EQ(size["record_unit"], "g");
  EXPECT_NEAR(size["record_value"].get<double>(), kStepG, 5 * sd_g);

  // VRW: white noise of sd sigma at fs has N = sigma / sqrt(fs) (m/s/sqrt(s); x 60 per sqrt(h)).
  // The white axis, N within 3 % (the AVAR at tau0 alone has a relative sd of ~0.3 % here).
  const nlohmann::json& y = j["columns"][2];
  EXPECT_EQ(y["verdict"]["effect"], "none") << y["verdict"];
  const nlohmann::json& n = y["baseline"]["coefficients"]["N"];
  EXPECT_EQ(n["unit"], "m/s/sqrt(h)");
  const double vrw = kAccelSigmaG * kGravity / std::sqrt(kRateHz) * 60.0;
  EXPECT_NEAR(n["value"].get<double>(), vrw, 0.03 * vrw);
}

TEST_F(ImuDiagnoseCommandTest, ASensorModelIsAGyrosAndOneColumnIsValidatedAlone) {
  EXPECT_EQ(Run("--imu --units deg/s --preset tg100 --trials 3"), 2);
  EXPECT_NE(Read("err.txt").find("Accel_X_g is an accelerometer axis; --preset and --sensor describe a gyro"),
            std::string::npos)
      << Read("err.txt");
  EXPECT_EQ(Run("--imu --units deg/s --validate-on imu.csv"), 2);
  EXPECT_EQ(Run("--column Accel_X_g --validate-on imu.csv"), 2);
  EXPECT_NE(Read("err.txt").find("--validate-on checks one gyro column"), std::string::npos) << Read("err.txt");
}

// diagnose reports in deg/h and mg beside the record's unit: the output-unit options are refused.
TEST_F(ImuDiagnoseCommandTest, OutputUnitOptionsAreRefused) {
  for (const std::string option : {"--out-units deg/s", "--accel-out-units g"}) {
    EXPECT_EQ(Run("--column Accel_X_g --trials 3 " + option + " --json out.json"), 2) << option;
    const std::string name = option.substr(0, option.find(' '));
    EXPECT_NE(Read("err.txt").find(name + " does not apply to diagnose"), std::string::npos) << Read("err.txt");
    EXPECT_FALSE(fs::exists(dir_ / "out.json")) << option;
  }
}

}  // namespace
}  // namespace allanlab::app
