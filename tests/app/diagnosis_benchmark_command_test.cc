// Smoke test of `allanlab diagnosis-benchmark`: three tiny recordings end to end (draw, spec,
// simulate, diagnose as a child process, score, tables), the same tables for one and two threads
// and for one and two concurrent diagnoses, and a refused command line that writes nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/support/command_test.h"

namespace allanlab::app {
namespace {

class DiagnosisBenchmarkCommandTest : public testing_support::CommandTest {
 protected:
  DiagnosisBenchmarkCommandTest() : CommandTest("allanlab_diagnosis_benchmark", "diagnosis-benchmark") {}
  std::string Args(const std::string& out, int jobs) {
    std::ostringstream a;
    a << "--recordings 3 --seed 3 --min-duration 60 --max-duration 120 --max-samples 30000 --no-plot --jobs "
      << jobs << " --out-dir " << Path(out) << " --work-dir " << Path(out + "_work");
    return a.str();
  }
};

TEST_F(DiagnosisBenchmarkCommandTest, WritesTheTablesDeterministically) {
  ASSERT_EQ(Run(Args("a", 2)), 0) << Read("err.txt");
  const std::string csv = Read("a/benchmark.csv");
  const std::string body = testing_support::WithoutCommentLines(csv);
  int lines = 0;
  for (char ch : body) lines += ch == '\n';
  EXPECT_EQ(lines, 4) << body;  // header + 3 recordings
  EXPECT_NE(csv.find("# seed: 3"), std::string::npos);
  EXPECT_NE(csv.find("# command: "), std::string::npos);
  const std::string md = Read("a/benchmark.md");
  for (const char* section : {"## Targets", "## Confusion matrix", "## Controls", "## Localization",
                              "## Held-out gap shrinkage", "## Recordings", "## Provenance"}) {
    EXPECT_NE(md.find(section), std::string::npos) << section;
  }
  // The records are deleted once diagnosed; specs and diagnoses stay in the work directory.
  EXPECT_FALSE(std::filesystem::exists(dir_ / "a_work" / "rec0.f64"));
  EXPECT_TRUE(std::filesystem::exists(dir_ / "a_work" / "rec0.yaml"));
  EXPECT_TRUE(std::filesystem::exists(dir_ / "a_work" / "rec0.diagnosis.json"));

  // One thread per diagnosis (inherited by the child processes), one diagnosis at a time.
  ::setenv("OMP_NUM_THREADS", "1", 1);
  const int code = Run(Args("b", 1));
  ::unsetenv("OMP_NUM_THREADS");
  ASSERT_EQ(code, 0) << Read("err.txt");
  EXPECT_EQ(testing_support::WithoutCommentLines(Read("b/benchmark.csv")), body);
}

TEST_F(DiagnosisBenchmarkCommandTest, RefusesBadOptionsAndWritesNothing) {
  EXPECT_EQ(Run("--recordings 0 --no-plot --out-dir " + Path("c")), 2);
  EXPECT_NE(Read("err.txt").find("--recordings"), std::string::npos) << Read("err.txt");
  EXPECT_FALSE(std::filesystem::exists(dir_ / "c" / "benchmark.csv"));
  EXPECT_EQ(Run("--min-duration 100 --max-duration 50 --no-plot --out-dir " + Path("c")), 2);
  EXPECT_FALSE(std::filesystem::exists(dir_ / "c" / "benchmark.csv"));
}

// The independent generator end to end: three short recordings (a control, then two effects in
// turn), the injected real recordings skipped with a message when the data directory is absent,
// and the two generators side by side.
TEST_F(DiagnosisBenchmarkCommandTest, IndependentGeneratorAndBothSideBySide) {
  const std::string common = "--recordings 3 --seed 5 --no-plot --jobs 2 --independent-min-duration 120 "
                             "--independent-max-duration 150 --min-duration 60 --max-duration 90 --max-samples 20000 ";
  ASSERT_EQ(Run(common + "--generator independent --real-recordings 2 --data-dir " + Path("no_such_dir") +
                " --out-dir " + Path("i") + " --work-dir " + Path("i_work")),
            0)
      << Read("err.txt");
  EXPECT_NE(Read("err.txt").find("real recordings skipped: no ADIS16405 recordings under"), std::string::npos)
      << Read("err.txt");
  EXPECT_FALSE(std::filesystem::exists(dir_ / "i" / "benchmark.csv"));
  const std::string csv = testing_support::WithoutCommentLines(Read("i/benchmark_independent.csv"));
  EXPECT_NE(csv.find(",independent,"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",control,"), std::string::npos) << csv;
  EXPECT_NE(csv.find("design="), std::string::npos) << csv;
  const std::string md = Read("i/benchmark_independent.md");
  for (const char* text : {"## Targets", "Wilson 95 % interval clears it", "## Real recordings with an injected effect",
                           "skipped: no ADIS16405", "--model N,B,K"}) {
    EXPECT_NE(md.find(text), std::string::npos) << text;
  }
  ASSERT_EQ(Run(common + "--generator both --out-dir " + Path("b2") + " --work-dir " + Path("b2_work")), 0) << Read("err.txt");
  const std::string side = Read("b2/benchmark_generators.md");
  EXPECT_NE(side.find("| target | sim | met | independent | met |"), std::string::npos) << side;
  EXPECT_TRUE(std::filesystem::exists(dir_ / "b2" / "benchmark.csv"));
  // The independent table of `both` is the independent run's (same seed, same draw).
  EXPECT_EQ(testing_support::WithoutCommentLines(Read("b2/benchmark_independent.csv")), csv);
  EXPECT_EQ(Run("--generator other --no-plot --out-dir " + Path("c2")), 2);
  EXPECT_NE(Read("err.txt").find("--generator must be sim, independent or both"), std::string::npos);
}

// The injected real recordings read the ADIS16405 files as they are laid out in the data directory
// (time column, gyro columns in deg/s that name no unit): two small stand-ins, one effect injected.
TEST_F(DiagnosisBenchmarkCommandTest, InjectsAnEffectIntoRealRecordings) {
  const std::filesystem::path adis = dir_ / "data" / "real" / "adis16405";
  std::filesystem::create_directories(adis);
  for (const char* name : {"adis_16405_imu1.csv.xz", "adis_16405_imu2.csv.xz"}) {
    std::ofstream f(adis / name);  // plain text: the reader recognises compression by its bytes, not the name
    f << "t_s,Gyro_X,Gyro_Y,Gyro_Z\n";
    for (int i = 0; i < 9000; ++i) {
      const double w = 0.05 * std::sin(0.7 * i) + 0.02 * std::cos(1.9 * i + 0.3 * (i % 7));
      f << i / 100.0 << ',' << w << ',' << -w << ',' << 0.5 * w << '\n';
    }
  }
  ASSERT_EQ(Run("--generator independent --recordings 1 --real-recordings 1 --real-segment 60 --seed 2 --no-plot "
                "--data-dir " + Path("data") + " --out-dir " + Path("r") + " --work-dir " + Path("r_work")),
            0)
      << Read("err.txt");
  const std::string md = Read("r/benchmark_independent.md");
  EXPECT_NE(md.find("1 from 6 segments of 60 s"), std::string::npos) << md;
}

}  // namespace
}  // namespace allanlab::app
