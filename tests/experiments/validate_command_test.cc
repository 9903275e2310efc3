// `allanlab validate`: the quick set passes against the committed golden tables, and a 3 % scale
// error injected into the Allan estimates (ALLANLAB_INJECT_AVAR_SCALE, experiments/avar_bias.h)
// makes it fail, naming what moved. Also --update and the refusals.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/support/read_file.h"

namespace allanlab::app {
namespace {

namespace fs = std::filesystem;

class ValidateCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / "allanlab_validate";
    dir_ += ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  int Run(const std::string& env, const std::string& args) {
    std::ostringstream command;
    command << env << ' ' << ALLANLAB_BINARY << ' ' << args << " > '" << (dir_ / "out.txt").string()
            << "' 2> '" << (dir_ / "err.txt").string() << "'";
    const int status = std::system(command.str().c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  std::string Read(const std::string& name) { return testing_support::ReadAll(dir_ / name); }

  fs::path dir_;
};

TEST_F(ValidateCommandTest, InjectedScaleErrorIsARegression) {
  ASSERT_EQ(Run("ALLANLAB_INJECT_AVAR_SCALE=1.03", "validate --quick --threads 2"), 1)
      << Read("out.txt") << Read("err.txt");
  EXPECT_NE(Read("out.txt").find("moved: avar_bias_quick point 0 avar_ratio/overlapping/m=1: "),
            std::string::npos)
      << Read("out.txt");
  EXPECT_NE(Read("err.txt").find("allanlab validate: error: regression: "), std::string::npos)
      << Read("err.txt");
}

TEST_F(ValidateCommandTest, UpdateWritesGoldenTablesThatThenPass) {
  const std::string specs = (dir_ / "specs").string();
  fs::create_directories(dir_ / "specs/quick");
  std::ofstream(dir_ / "specs/quick/tiny.yaml")
      << "name: tiny\ndriver: avar_bias\nseed: 5\ntrials: 30\n"
         "sensor: {model: {name: w, sample_rate: 10 Hz, terms: [{type: arw, N: 1 deg/sqrt(h)}]}}\n"
         "record: {samples: 1024}\n";
  const std::string golden = (dir_ / "golden").string();
  EXPECT_EQ(Run("", "validate --quick --specs " + specs + " --golden " + golden), 1);
  EXPECT_NE(Read("err.txt").find("no golden table"), std::string::npos) << Read("err.txt");
  ASSERT_EQ(Run("", "validate --quick --update --specs " + specs + " --golden " + golden), 0)
      << Read("err.txt");
  const std::string table = Read("golden/tiny.csv");
  EXPECT_NE(table.find("# command: "), std::string::npos);
  EXPECT_NE(table.find("0,avar_ratio/overlapping/m=1,30,"), std::string::npos) << table;
  EXPECT_EQ(Run("", "validate --quick --threads 1 --specs " + specs + " --golden " + golden), 0)
      << Read("out.txt") << Read("err.txt");
  EXPECT_NE(Read("out.txt").find("validate: ok"), std::string::npos);
  // A bad spec is refused before anything runs.
  std::ofstream(dir_ / "specs/quick/bad.yaml") << "name: bad\n";
  EXPECT_EQ(Run("", "validate --quick --specs " + specs + " --golden " + golden), 2);
  EXPECT_NE(Read("err.txt").find("bad.yaml"), std::string::npos) << Read("err.txt");
}

}  // namespace
}  // namespace allanlab::app
