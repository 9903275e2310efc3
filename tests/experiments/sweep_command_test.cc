// End-to-end tests of `allanlab sweep`: the avar_bias report, clear refusals, and resume after a
// SIGKILL in the middle of a run giving the same table as an uninterrupted run.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "tests/support/command_test.h"
#include "tests/support/read_file.h"

namespace allanlab::app {
namespace {

namespace fs = std::filesystem;

// 2^14-sample white + flicker records, octave taus, both Allan estimators.
std::string SpecText(int trials, int seed) {
  std::ostringstream s;
  s << "name: bias\ndriver: avar_bias\nseed: " << seed << "\ntrials: " << trials
    << "\nsensor: {model: {name: m, sample_rate: 100 Hz, terms: [{type: arw, N: 0.1 deg/sqrt(h)}, "
       "{type: bias_instability, B: 1 deg/h}]}}\n"
       "record: {samples: 16384}\nestimators: [overlapping, nonoverlapping]\n"
       "sweep: {parameters: [{path: 'sensor.terms[1].B', values: [1 deg/h, 3 deg/h]}]}\n";
  return s.str();
}

class SweepCommandTest : public testing_support::CommandTest {
 protected:
  SweepCommandTest() : CommandTest("allanlab_sweep") {}
  std::string P(const std::string& name) { return (dir_ / name).string(); }
};

TEST_F(SweepCommandTest, WritesTheReportAndRemovesTheCheckpoint) {
  std::ofstream(dir_ / "spec.yaml") << SpecText(20, 3);
  ASSERT_EQ(Run("sweep " + P("spec.yaml") + " --out " + P("out") + " --threads 2"), 0)
      << Read("err.txt");
  const std::string csv = Read("out/bias.csv");
  EXPECT_NE(csv.find("# git_sha: "), std::string::npos);
  EXPECT_NE(csv.find("# command: "), std::string::npos);
  EXPECT_NE(csv.find("avar_ratio/overlapping/m=1,20,"), std::string::npos) << csv;
  EXPECT_NE(csv.find("sensor.terms[1].B=3 deg/h"), std::string::npos);
  EXPECT_NE(Read("out/bias.md").find("| avar_ratio/nonoverlapping/m=1 |"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir_ / "out/bias.checkpoint"));
  EXPECT_NE(Read("out.txt").find("2 points x 20 trials (0 failed, 0 resumed)"), std::string::npos)
      << Read("out.txt");
  // Same seed, one thread: the same table.
  ASSERT_EQ(Run("sweep " + P("spec.yaml") + " --out " + P("one") + " --threads 1 --batch 3"), 0);
  EXPECT_EQ(testing_support::WithoutCommentLines(csv),
            testing_support::WithoutCommentLines(Read("one/bias.csv")));
}

TEST_F(SweepCommandTest, RefusesBadSpecsWithOneLineNamingTheKey) {
  std::string bad = SpecText(20, 3);
  bad.replace(bad.find("trials: 20"), 10, "trials: -4");
  std::ofstream(dir_ / "bad.yaml") << bad;
  EXPECT_EQ(Run("sweep " + P("bad.yaml") + " --out " + P("out")), 2);
  const std::string err = Read("err.txt");
  EXPECT_NE(err.find("allanlab sweep: error: "), std::string::npos) << err;
  EXPECT_NE(err.find("trials: must be >= 1"), std::string::npos) << err;
  EXPECT_EQ(err.find('\n'), err.size() - 1) << err;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
  EXPECT_EQ(Run("sweep " + P("missing.yaml")), 2);
  EXPECT_NE(Read("err.txt").find("missing.yaml"), std::string::npos);
  std::ofstream(dir_ / "ok.yaml") << SpecText(2, 3);
  EXPECT_EQ(Run("sweep " + P("ok.yaml") + " --threads -1"), 2);
}

TEST_F(SweepCommandTest, ResumeAfterSigkillMatchesAnUninterruptedRun) {
  std::ofstream(dir_ / "spec.yaml") << SpecText(250, 11);
  ASSERT_EQ(Run("sweep " + P("spec.yaml") + " --out " + P("ref") + " --threads 2"), 0)
      << Read("err.txt");
  const std::string reference = testing_support::WithoutCommentLines(Read("ref/bias.csv"));
  ASSERT_FALSE(reference.empty());

  // The interrupted run: one thread, small batches; killed once the store holds a few batches.
  const std::string spec = P("spec.yaml"), out = P("run");
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    ::dup2(null, 2);
    ::execl(ALLANLAB_BINARY, ALLANLAB_BINARY, "sweep", spec.c_str(), "--out", out.c_str(),
            "--threads", "1", "--batch", "8", static_cast<char*>(nullptr));
    ::_exit(127);
  }
  const fs::path store = dir_ / "run/bias.checkpoint";
  bool still_running = false;
  for (int i = 0; i < 6000; ++i) {
    std::error_code ec;
    if (fs::exists(store, ec) && fs::file_size(store, ec) > 4000) {
      still_running = ::waitpid(child, nullptr, WNOHANG) == 0;
      break;
    }
    if (::waitpid(child, nullptr, WNOHANG) != 0) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_TRUE(still_running) << "the sweep ended before it could be killed";
  ASSERT_EQ(::kill(child, SIGKILL), 0);
  int status = 0;
  ::waitpid(child, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status));
  EXPECT_FALSE(fs::exists(dir_ / "run/bias.csv"));
  // Without --resume the store is not overwritten.
  EXPECT_EQ(Run("sweep " + spec + " --out " + out), 1);
  EXPECT_NE(Read("err.txt").find("--resume"), std::string::npos) << Read("err.txt");

  ASSERT_EQ(Run("sweep " + spec + " --out " + out + " --threads 2 --resume"), 0) << Read("err.txt");
  const std::string summary = Read("out.txt");
  const std::size_t at = summary.find(" failed, ");
  ASSERT_NE(at, std::string::npos) << summary;
  const long resumed = std::strtol(summary.c_str() + at + 9, nullptr, 10);
  EXPECT_GT(resumed, 0) << summary;
  EXPECT_LT(resumed, 500) << summary;
  EXPECT_EQ(reference, testing_support::WithoutCommentLines(Read("run/bias.csv")));
  EXPECT_FALSE(fs::exists(store));
}

TEST_F(SweepCommandTest, ResumeRefusesAFileThatIsNotAStore) {
  std::ofstream(dir_ / "a.yaml") << SpecText(4, 1);
  std::ofstream(dir_ / "junk.ckpt") << "not a checkpoint\n";
  EXPECT_EQ(Run("sweep " + P("a.yaml") + " --checkpoint " + P("junk.ckpt") + " --out " + P("o") +
                " --resume"),
            1);
  EXPECT_NE(Read("err.txt").find("is not an allanlab checkpoint"), std::string::npos)
      << Read("err.txt");
  EXPECT_EQ(Read("junk.ckpt"), "not a checkpoint\n");
}

}  // namespace
}  // namespace allanlab::app
