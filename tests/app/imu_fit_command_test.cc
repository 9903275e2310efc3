// `allanlab fit --imu`: one fit per gyro and accelerometer column of one record, a table each, one
// JSON and one Kalibr YAML for the whole IMU, on a small generated record of white noise whose
// noise densities are known in closed form (N = sigma / sqrt(fs)).
#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/wait.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <regex>
#include <string>

#include "tests/support/read_file.h"

namespace allanlab::app {
namespace {

namespace fs = std::filesystem;
using testing_support::ReadAll;

std::string Quote(const std::string& s) { return "'" + s + "'"; }

// The value of `key: value` in the YAML text, NaN when absent.
double YamlValue(const std::string& yaml, const std::string& key) {
  std::smatch m;
  if (!std::regex_search(yaml, m, std::regex("\n" + key + ": ([-+0-9.eE]+)"))) return NAN;
  return std::stod(m[1]);
}

TEST(ImuFitCommandTest, EveryAxisFittedAndOneYamlForTheImu) {
  std::string templ = (fs::path(::testing::TempDir()) / "imu_fit_command_test.XXXXXX").string();
  ASSERT_NE(::mkdtemp(templ.data()), nullptr);
  const fs::path dir = templ;
  constexpr int kSamples = 20000;
  constexpr double kRateHz = 100.0;
  constexpr double kGyroSigmaDegPerS = 0.05, kAccelSigmaG = 0.002;
  std::mt19937_64 engine(3);
  std::normal_distribution<double> normal;
  {
    std::ofstream csv(dir / "imu.csv");
    csv.precision(17);
    csv << "t_s,Gyro_X,Accel_X\n";
    for (int k = 0; k < kSamples; ++k) {
      csv << k / kRateHz << "," << 0.1 + kGyroSigmaDegPerS * normal(engine) << ","
          << 1.0 + kAccelSigmaG * normal(engine) << "\n";
    }
  }
  const std::string command = "cd " + Quote(dir.string()) + " && " + Quote(ALLANLAB_BINARY) +
                              " fit imu.csv --imu --units deg/s --accel-units g --terms N,K --json fit.json "
                              "--kalibr imu.yaml >out.txt 2>err.txt";
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << ReadAll((dir / "err.txt").string());
  const std::string out = ReadAll((dir / "out.txt").string());
  EXPECT_NE(out.find("# column Gyro_X (gyro, deg/s in)"), std::string::npos) << out;
  EXPECT_NE(out.find("# column Accel_X (accelerometer, g in)"), std::string::npos) << out;
  EXPECT_NE(out.find("N velocity random walk (VRW)"), std::string::npos) << out;
  EXPECT_NE(out.find("m/s/sqrt(h)"), std::string::npos) << out;

  // White noise of sigma per sample at fs: N = sigma / sqrt(fs). The estimate from 2e4 samples
  // has a relative standard deviation near 1/sqrt(2 * 2e4) = 0.5 %; 3 % is 6 of them.
  const double gyro_n_si = kGyroSigmaDegPerS * M_PI / 180.0 / std::sqrt(kRateHz);  // rad/sqrt(s)
  const double accel_n_si = kAccelSigmaG * 9.80665 / std::sqrt(kRateHz);           // m/s/sqrt(s)
  const nlohmann::json j = nlohmann::json::parse(ReadAll((dir / "fit.json").string()));
  ASSERT_EQ(j["columns"].size(), 2u);
  EXPECT_EQ(j["columns"][0]["column"], "Gyro_X");
  EXPECT_EQ(j["columns"][1]["sensor"], "accelerometer");
  const nlohmann::json& gyro_n = j["columns"][0]["coefficients"]["N"];
  EXPECT_EQ(gyro_n["unit"], "deg/sqrt(h)");
  EXPECT_NEAR(gyro_n["value"].get<double>(), gyro_n_si * 180.0 / M_PI * 60.0, 0.03 * gyro_n_si * 180.0 / M_PI * 60.0);
  const nlohmann::json& accel_n = j["columns"][1]["coefficients"]["N"];
  EXPECT_EQ(accel_n["unit"], "m/s/sqrt(h)");
  EXPECT_EQ(accel_n["name"], "velocity random walk (VRW)");
  EXPECT_NEAR(accel_n["value"].get<double>(), accel_n_si * 60.0, 0.03 * accel_n_si * 60.0);

  const std::string yaml = ReadAll((dir / "imu.yaml").string());
  EXPECT_NEAR(YamlValue(yaml, "gyroscope_noise_density"), gyro_n_si, 0.03 * gyro_n_si) << yaml;
  EXPECT_NEAR(YamlValue(yaml, "accelerometer_noise_density"), accel_n_si, 0.03 * accel_n_si) << yaml;
  // No random walk in white noise: a small positive bound, never a zero a filter would trust.
  EXPECT_GT(YamlValue(yaml, "gyroscope_random_walk"), 0.0) << yaml;
  EXPECT_GT(YamlValue(yaml, "accelerometer_random_walk"), 0.0) << yaml;
  EXPECT_LT(YamlValue(yaml, "accelerometer_random_walk"), accel_n_si) << yaml;
  EXPECT_EQ(YamlValue(yaml, "update_rate"), 100.0);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace allanlab::app
