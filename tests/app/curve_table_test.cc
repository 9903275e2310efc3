// Published Allan curves: deviations or variances, in any rate unit, rows beyond the record
// skipped and named, bad cells refused with their line.
#include "app/input/curve_table.h"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "app/commands/subcommand.h"
#include "sim/units.h"

namespace allanlab::app {
namespace {

namespace fs = std::filesystem;

class CurveTableTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string templ = (fs::path(::testing::TempDir()) / "curve_table_test.XXXXXX").string();
    ASSERT_NE(::mkdtemp(templ.data()), nullptr);
    dir_ = templ;
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Write(const std::string& name, const std::string& text) const {
    const std::string path = (dir_ / name).string();
    std::ofstream(path) << text;
    return path;
  }
  fs::path dir_;
};

TEST_F(CurveTableTest, DeviationsAndVariancesInTheirUnits) {
  // 100 Hz, 1000 s: m = 10, 100, 1000; the 600 s row is beyond half the record.
  const std::string text =
      "# a published curve\ntau_s,adev_x,avar\n0.1,36,1e-4\n1,3.6,1e-6\n10,0.36,1e-8\n"
      "600,0.1,1e-9\n";
  CurveTableOptions o{Write("c.csv", text), "adev_x", RateUnit::kDegPerHour, 1000, 100};
  CurveTable t;
  CurveTableError e;
  ASSERT_TRUE(ReadCurveTable(o, &t, &e)) << e.message;
  EXPECT_FALSE(t.variance);
  ASSERT_EQ(t.curve.size(), 3u);
  EXPECT_EQ(t.curve.m, (std::vector<std::int64_t>{10, 100, 1000}));
  EXPECT_EQ(t.curve.num_samples, 100000);
  const double dev = units::DegPerHour(3.6);
  EXPECT_NEAR(t.curve.avar[1], dev * dev, 1e-15 * dev * dev);
  ASSERT_EQ(t.skipped.size(), 1u);
  EXPECT_EQ(t.skipped[0], "line 6: tau 600 s is beyond half the record (1000 s)");

  o.column = "avar";
  o.unit = RateUnit::kRadPerSecond;
  ASSERT_TRUE(ReadCurveTable(o, &t, &e)) << e.message;
  EXPECT_TRUE(t.variance);
  EXPECT_EQ(t.curve.avar[1], 1e-6);
}

TEST_F(CurveTableTest, BadTablesFailWithTheirLine) {
  CurveTableOptions o{Write("bad.csv", "tau_s,adev_x\n1,2\n2,abc\n"), "adev_x",
                      RateUnit::kDegPerHour, 1000, 100};
  CurveTable t;
  CurveTableError e;
  EXPECT_FALSE(ReadCurveTable(o, &t, &e));
  EXPECT_EQ(e.exit_code, kExitRuntimeError);
  EXPECT_EQ(e.message, o.path + ": line 3: adev_x 'abc' is not a number > 0");
  o.path = Write("cols.csv", "tau,adev_y\n1,2\n");
  EXPECT_FALSE(ReadCurveTable(o, &t, &e));
  EXPECT_EQ(e.exit_code, kExitUsageError);
  EXPECT_EQ(e.message, o.path + ": line 1: the header needs a tau column (tau_s or tau) and adev_x "
                                "(--curve-column); it has tau, adev_y");
  o.path = Write("far.csv", "tau_s adev_x\n900 1\n");
  EXPECT_FALSE(ReadCurveTable(o, &t, &e));
  EXPECT_EQ(e.message, o.path + ": no usable rows in adev_x (1 read; line 2: tau 900 s is beyond "
                                "half the record (1000 s))");
}

}  // namespace
}  // namespace allanlab::app
