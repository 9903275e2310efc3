// `allanlab diagnose --imu`: every gyro column of one record diagnosed, accelerometer columns left
// out with a warning (named ones refused), one JSON with a section per column.
#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/wait.h>

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

TEST(ImuDiagnoseCommandTest, EveryGyroColumnDiagnosed) {
  std::string templ = (fs::path(::testing::TempDir()) / "imu_diagnose_command_test.XXXXXX").string();
  ASSERT_NE(::mkdtemp(templ.data()), nullptr);
  const fs::path dir = templ;
  std::mt19937_64 engine(5);
  std::normal_distribution<double> normal;
  {
    std::ofstream csv(dir / "imu.csv");
    csv.precision(17);
    csv << "t_s,Gyro_X,Gyro_Y,Accel_X_g\n";
    for (int k = 0; k < 4096; ++k) {
      csv << k / 100.0 << "," << 0.05 * normal(engine) << "," << 0.03 * normal(engine) << ","
          << 1.0 + 0.002 * normal(engine) << "\n";
    }
  }
  const auto run = [&](const std::string& args) {
    const std::string command = "cd " + Quote(dir.string()) + " && " + Quote(ALLANLAB_BINARY) + " diagnose imu.csv " +
                                args + " >out.txt 2>err.txt";
    const int status = std::system(command.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  };
  ASSERT_EQ(run("--imu --units deg/s --trials 3 --json d.json"), 0) << ReadAll((dir / "err.txt").string());
  EXPECT_NE(ReadAll((dir / "err.txt").string()).find("Accel_X_g not diagnosed"), std::string::npos);
  const std::string out = ReadAll((dir / "out.txt").string());
  EXPECT_NE(out.find("# column Gyro_X\nin plain words:"), std::string::npos) << out;
  EXPECT_NE(out.find("# column Gyro_Y\nin plain words:"), std::string::npos) << out;
  const nlohmann::json j = nlohmann::json::parse(ReadAll((dir / "d.json").string()));
  ASSERT_EQ(j["columns"].size(), 2u);
  EXPECT_EQ(j["columns"][1]["column"], "Gyro_Y");
  EXPECT_TRUE(j["columns"][1].contains("verdict"));
  EXPECT_EQ(run("--columns Gyro_X,Accel_X_g --units deg/s --trials 3"), 2);
  EXPECT_NE(ReadAll((dir / "err.txt").string()).find("accelerometer column(s)"), std::string::npos);
  EXPECT_EQ(run("--imu --units deg/s --validate-on imu.csv"), 2);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace allanlab::app
