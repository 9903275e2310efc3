// Several columns of one record (an IMU's gyro and accelerometer axes): column choice by name,
// accelerometer units, and `allanlab avar --columns/--imu` end to end on small generated files.
#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "app/input/accel_units.h"
#include "app/reports/allan_plot.h"
#include "app/input/imu_columns.h"
#include "tests/support/read_file.h"

namespace allanlab::app {
namespace {

namespace fs = std::filesystem;
using testing_support::ReadAll;

TEST(ImuColumnsTest, NamesSayGyroOrAccelerometer) {
  EXPECT_EQ(ImuSensorOfColumn("Gyro_X"), ImuSensor::kGyro);
  EXPECT_EQ(ImuSensorOfColumn("gyr_y"), ImuSensor::kGyro);
  EXPECT_EQ(ImuSensorOfColumn("field.angular_velocity.z"), ImuSensor::kGyro);
  EXPECT_EQ(ImuSensorOfColumn("Accel_X"), ImuSensor::kAccelerometer);
  EXPECT_EQ(ImuSensorOfColumn("acc_z_mps2"), ImuSensor::kAccelerometer);
  EXPECT_EQ(ImuSensorOfColumn("field.linear_acceleration.x"), ImuSensor::kAccelerometer);
  EXPECT_EQ(ImuSensorOfColumn("temperature"), std::nullopt);
  EXPECT_EQ(ImuSensorOfColumn("t_s"), std::nullopt);
  std::vector<std::string> columns;
  std::string why;
  ASSERT_TRUE(ChooseImuColumns({"t_s", "Gyro_X", "temp", "Accel_Z"}, 0, &columns, &why));
  EXPECT_EQ(columns, (std::vector<std::string>{"Gyro_X", "Accel_Z"}));
  EXPECT_FALSE(ChooseImuColumns({"t_s", "x", "y"}, 0, &columns, &why));
  EXPECT_NE(why.find("--columns"), std::string::npos) << why;
  ASSERT_TRUE(ParseColumnList(" Gyro_X, Gyro_Y ,2", &columns, &why));
  EXPECT_EQ(columns, (std::vector<std::string>{"Gyro_X", "Gyro_Y", "2"}));
  EXPECT_FALSE(ParseColumnList("Gyro_X,,Gyro_Y", &columns, &why));
}

TEST(AccelUnitsTest, SpellingsAndFactors) {
  AccelUnit unit;
  for (const char* text : {"m/s^2", "m/s2", "m/s\xC2\xB2", "mps2", "m s^-2", "M/S^2"}) {
    ASSERT_TRUE(ParseAccelUnit(text, &unit, nullptr)) << text;
    EXPECT_EQ(unit, AccelUnit::kMeterPerSecond2) << text;
  }
  ASSERT_TRUE(ParseAccelUnit("g", &unit, nullptr));
  EXPECT_EQ(unit, AccelUnit::kG);
  ASSERT_TRUE(ParseAccelUnit("mg", &unit, nullptr));
  EXPECT_EQ(unit, AccelUnit::kMilliG);
  std::string why;
  EXPECT_FALSE(ParseAccelUnit("ug", &unit, &why));
  EXPECT_NE(why.find("m/s^2, g or mg"), std::string::npos) << why;
  // The CGPM standard gravity, not a local one.
  EXPECT_EQ(AccelToSi(AccelUnit::kG, 1.0), 9.80665);
  EXPECT_DOUBLE_EQ(AccelFromSi(AccelUnit::kMilliG, 9.80665), 1000.0);
  EXPECT_EQ(AccelUnitFromColumnName("Accel_X_g"), "g");
  EXPECT_EQ(AccelUnitFromColumnName("acc_x [m/s^2]"), "m/s^2");
  EXPECT_EQ(AccelUnitFromColumnName("acc_y_mps2"), "m/s^2");
  EXPECT_EQ(AccelUnitFromColumnName("ax_mg"), "mg");
  EXPECT_EQ(AccelUnitFromColumnName("field.linear_acceleration.y"), "m/s^2");
  EXPECT_EQ(AccelUnitFromColumnName("Accel_X"), "");
  // VRW 1 m/s/sqrt(h) = 1/60 m/s/sqrt(s); bias instability 1 mg.
  EXPECT_DOUBLE_EQ(AccelToDatasheetUnit(estimators::Coefficient::kN, 1.0 / 60.0), 1.0);
  EXPECT_DOUBLE_EQ(AccelToDatasheetUnit(estimators::Coefficient::kB, 9.80665e-3), 1.0);
  EXPECT_DOUBLE_EQ(AccelToDatasheetUnit(estimators::Coefficient::kK, 1.0 / 60.0), 1.0);
}

std::string Quote(const std::string& s) { return "'" + s + "'"; }

std::string Number(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

// The overlapping AVAR at m = 1 by its definition, 1/2 <(y[k+1] - y[k])^2>.
double AvarAtOne(const std::vector<double>& y) {
  double sum = 0;
  for (std::size_t k = 0; k + 1 < y.size(); ++k) sum += (y[k + 1] - y[k]) * (y[k + 1] - y[k]);
  return sum / (2.0 * static_cast<double>(y.size() - 1));
}

class ImuAvarCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string templ = (fs::path(::testing::TempDir()) / "imu_avar_command_test.XXXXXX").string();
    ASSERT_NE(::mkdtemp(templ.data()), nullptr);
    dir_ = templ;
    std::mt19937_64 engine(11);
    std::normal_distribution<double> normal;
    for (int k = 0; k < kSamples; ++k) {
      gx_.push_back(0.1 + 0.05 * normal(engine));
      gy_.push_back(-0.2 + 0.03 * normal(engine));
      ax_.push_back(1.0 + 0.002 * normal(engine));
    }
    // Accel_Y_mps2 is Accel_X_g in m/s^2: the same signal stated in another unit.
    std::string text = "t_s,Gyro_X,Gyro_Y,temp,Accel_X_g,Accel_Y_mps2\n";
    for (int k = 0; k < kSamples; ++k) {
      text += Number(k / 100.0) + "," + Number(gx_[k]) + "," + Number(gy_[k]) + ",25," + Number(ax_[k]) +
              "," + Number(ax_[k] * 9.80665) + "\n";
    }
    Write("imu.csv", text);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
  void Write(const std::string& name, const std::string& bytes) const {
    std::ofstream(Path(name), std::ios::binary) << bytes;
  }
  struct RunResult {
    int exit_code = -1;
    std::string out, err;
  };
  RunResult Run(const std::string& args) const {
    const std::string command = "cd " + Quote(dir_.string()) + " && " + Quote(ALLANLAB_BINARY) + " " + args +
                                " >" + Quote(Path("stdout.txt")) + " 2>" + Quote(Path("stderr.txt"));
    const int status = std::system(command.c_str());
    RunResult r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = ReadAll(Path("stdout.txt"));
    r.err = ReadAll(Path("stderr.txt"));
    fs::remove(Path("stdout.txt"));
    fs::remove(Path("stderr.txt"));
    return r;
  }
  nlohmann::json Json(const std::string& name) const { return nlohmann::json::parse(ReadAll(Path(name))); }
  void ExpectError(const std::string& args, int code, const std::string& part) const {
    const RunResult r = Run(args + " --json out.json");
    EXPECT_EQ(r.exit_code, code) << args << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("allanlab avar: error: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(part), std::string::npos) << args << "\n" << r.err;
    EXPECT_FALSE(fs::exists(Path("out.json")));
  }

  static constexpr int kSamples = 2048;
  fs::path dir_;
  std::vector<double> gx_, gy_, ax_;
};

TEST_F(ImuAvarCommandTest, ImuTakesEveryGyroAndAccelerometerColumnWithItsUnits) {
  const RunResult r = Run("avar imu.csv --imu --units deg/s --json out.json --csv out.csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = Json("out.json");
  ASSERT_EQ(j["columns"].size(), 4u);
  const char* names[] = {"Gyro_X", "Gyro_Y", "Accel_X_g", "Accel_Y_mps2"};
  const char* sensors[] = {"gyro", "gyro", "accelerometer", "accelerometer"};
  const char* units[] = {"deg/s", "deg/s", "g", "m/s^2"};
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(j["columns"][k]["input"]["column"], names[k]);
    EXPECT_EQ(j["columns"][k]["input"]["sensor"], sensors[k]);
    EXPECT_EQ(j["columns"][k]["input"]["units"], units[k]);
    EXPECT_EQ(j["columns"][k]["input"]["rate_samples"], kSamples);
  }
  EXPECT_EQ(j["columns"][2]["units"]["dev"], "mg");
  EXPECT_EQ(j["columns"][0]["units"]["dev"], "deg/h");
  // m = 1 by the definition, in the output units: deg/s -> deg/h is 3600; g -> mg is 1000.
  const double gyro = std::sqrt(AvarAtOne(gx_)) * 3600.0;
  EXPECT_NEAR(j["columns"][0]["points"][0]["dev"].get<double>(), gyro, 1e-12 * gyro);
  const double accel = std::sqrt(AvarAtOne(ax_)) * 1000.0;
  EXPECT_NEAR(j["columns"][2]["points"][0]["dev"].get<double>(), accel, 1e-12 * accel);
  // The same signal stated in g and in m/s^2 gives the same curve in mg at every tau.
  const nlohmann::json& g = j["columns"][2]["points"];
  const nlohmann::json& mps2 = j["columns"][3]["points"];
  ASSERT_EQ(g.size(), mps2.size());
  for (std::size_t k = 0; k < g.size(); ++k) {
    EXPECT_NEAR(g[k]["dev"].get<double>(), mps2[k]["dev"].get<double>(), 1e-9 * g[k]["dev"].get<double>());
  }
  // One table per column on stdout, and the long CSV with the unit of each row.
  EXPECT_NE(r.out.find(", Accel_X_g, 2048 accelerometer samples"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("ADEV[mg]"), std::string::npos);
  const std::string csv = ReadAll(Path("out.csv"));
  EXPECT_NE(csv.find("\ncolumn,sensor,unit,m,tau_s,"), std::string::npos) << csv.substr(0, 2000);
  EXPECT_NE(csv.find("\nAccel_X_g,accelerometer,mg,1,0.01,"), std::string::npos);
}

TEST_F(ImuAvarCommandTest, ColumnsGiveTheCurvesOfOneColumnRuns) {
  ASSERT_EQ(Run("avar imu.csv --columns Gyro_Y,Accel_X_g --units deg/s --json several.json").exit_code, 0);
  ASSERT_EQ(Run("avar imu.csv --column Gyro_Y --units deg/s --json y.json").exit_code, 0);
  const nlohmann::json several = Json("several.json");
  const nlohmann::json one = Json("y.json");
  ASSERT_EQ(several["columns"].size(), 2u);
  EXPECT_EQ(several["columns"][0]["points"], one["points"]);
  // A comma list in --column reads the same columns.
  ASSERT_EQ(Run("avar imu.csv --column Gyro_Y,Accel_X_g --units deg/s --json comma.json").exit_code, 0);
  EXPECT_EQ(Json("comma.json")["columns"], several["columns"]);
  // One accelerometer axis by --column is read in its own units, as with --columns.
  const RunResult accel = Run("avar imu.csv --column Accel_X_g --json accel.json");
  ASSERT_EQ(accel.exit_code, 0) << accel.err;
  EXPECT_EQ(Json("accel.json")["columns"][0]["points"], several["columns"][1]["points"]);
  EXPECT_EQ(Json("accel.json")["columns"][0]["units"]["dev"], "mg");
}

TEST_F(ImuAvarCommandTest, StreamGivesEveryColumnsCurveInOnePass) {
  const RunResult r = Run("avar imu.csv --imu --units deg/s --stream --json stream.json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_EQ(Run("avar imu.csv --imu --units deg/s --ci simple --json memory.json").exit_code, 0);
  const nlohmann::json stream = Json("stream.json"), memory = Json("memory.json");
  ASSERT_EQ(stream["columns"].size(), 4u);
  EXPECT_NE(stream["provenance"]["estimator"].get<std::string>().find("--stream"), std::string::npos);
  // m = 1 by the definition (deg/s -> deg/h is 3600; g -> mg is 1000).
  const double gyro = std::sqrt(AvarAtOne(gy_)) * 3600.0;
  EXPECT_NEAR(stream["columns"][1]["points"][0]["dev"].get<double>(), gyro, 1e-12 * gyro);
  const double accel = std::sqrt(AvarAtOne(ax_)) * 1000.0;
  EXPECT_NEAR(stream["columns"][3]["points"][0]["dev"].get<double>(), accel, 1e-12 * accel);
  // Every column at every octave tau as the in-memory pass computes it (another algorithm: the
  // streaming estimator's running sums against the integrated record's differences).
  for (std::size_t c = 0; c < 4; ++c) {
    const nlohmann::json& s = stream["columns"][c]["points"];
    const nlohmann::json& m = memory["columns"][c]["points"];
    EXPECT_EQ(stream["columns"][c]["input"]["units"], memory["columns"][c]["input"]["units"]);
    ASSERT_EQ(s.size(), m.size()) << c;
    for (std::size_t k = 0; k < s.size(); ++k) {
      EXPECT_NEAR(s[k]["var"].get<double>(), m[k]["var"].get<double>(), 1e-10 * m[k]["var"].get<double>()) << c;
      EXPECT_EQ(s[k]["edf"], m[k]["edf"]) << c;
    }
  }
}

TEST_F(ImuAvarCommandTest, PlotHasEveryAxis) {
  std::string why;
  if (!FindGnuplot(&why)) GTEST_SKIP() << why;
  const RunResult r = Run("avar imu.csv --imu --units deg/s --plot imu.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_GT(fs::file_size(Path("imu.png")), 1000u);
}

TEST_F(ImuAvarCommandTest, BadChoicesAreOneLineErrors) {
  Write("acc.csv", "t_s,Gyro_X,Accel_X\n0,1,2\n0.01,2,3\n0.02,1,1\n0.03,3,1\n");
  ExpectError("avar acc.csv --imu --units deg/s", 2, "--accel-units m/s^2, g or mg");
  ExpectError("avar imu.csv --imu --units deg/s --accel-units mg", 2, "contradicts");
  ExpectError("avar imu.csv --imu", 2, "gyro column Gyro_X");
  ExpectError("avar imu.csv --imu --column Gyro_X --units deg/s", 2, "--imu");
  ExpectError("avar imu.csv --columns Gyro_X,nope --units deg/s", 2, "nope");
  ExpectError("avar imu.csv --columns Gyro_X,Gyro_X --units deg/s", 2, "twice");
  ExpectError("avar imu.csv --columns Gyro_X,Gyro_Y --units deg/s --stream --ci gr", 2, "--stream");
  ExpectError("avar imu.csv --accel-units kg --column Gyro_X --units deg/s", 2, "--accel-units");
  Write("plain.csv", "t_s,x,y\n0,1,2\n0.01,2,3\n0.02,1,1\n0.03,3,1\n");
  ExpectError("avar plain.csv --imu --units deg/s", 2, "no gyro or accelerometer column");
}

TEST_F(ImuAvarCommandTest, NonFiniteValueDropsTheWholeRow) {
  std::string text = "t_s,Gyro_X,Accel_X_g\n";
  for (int k = 0; k < 64; ++k) {
    text += Number(k / 100.0) + "," + (k == 10 ? std::string("nan") : Number(gx_[k])) + "," + Number(ax_[k]) + "\n";
  }
  Write("nan.csv", text);
  ExpectError("avar nan.csv --imu --units deg/s", 1, "line(s) 12");
  const RunResult r = Run("avar nan.csv --imu --units deg/s --drop-nonfinite --json out.json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = Json("out.json");
  EXPECT_EQ(j["columns"][0]["input"]["rate_samples"], 63);
  EXPECT_EQ(j["columns"][1]["input"]["rate_samples"], 63);
  EXPECT_EQ(j["columns"][1]["input"]["units_source"], "column Accel_X_g");
}

}  // namespace
}  // namespace allanlab::app
