// `allanlab validate`: the quick set passes against the committed golden tables, and a 3 % scale
// error injected into the Allan estimates or into the coefficients (experiments/injected_fault.h,
// through RunValidateCommand in this process) makes it fail, naming what moved. Also --update and
// the refusals, through the built binary.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <string>

#include "app/commands/validate_command.h"
#include "tests/support/read_file.h"

namespace allanlab::app {
namespace {

namespace fs = std::filesystem;

class ValidateCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / "allanlab_validate";
    dir_ += ::testing::UnitTest::GetInstance()->current_test_info()->name();
    // The process id too: two checkouts' suites running at once on one machine must not share
    // (and remove_all) each other's folder.
    dir_ += "_";
    dir_ += std::to_string(::getpid());
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

  // RunValidateCommand in this process with a fault in the drivers; stdout and stderr are
  // captured into out_ and err_.
  int RunWithFault(const std::string& specs, const experiments::InjectedFault& fault) {
    ValidateCommandOptions options;
    options.quick = true;
    options.threads = 2;
    options.specs_dir = specs;
    options.fault = fault;
    ::testing::internal::CaptureStdout();
    ::testing::internal::CaptureStderr();
    const int code = RunValidateCommand(options, "validate --quick --threads 2 --specs " + specs);
    out_ = ::testing::internal::GetCapturedStdout();
    err_ = ::testing::internal::GetCapturedStderr();
    return code;
  }
  std::string out_, err_;

  // A spec folder holding copies of some of the source tree's quick specs (compared with the
  // committed golden tables, which --golden defaults to).
  std::string QuickSubset(std::initializer_list<const char*> names) {
    const fs::path source = fs::path(ALLANLAB_TEST_DATA_DIR).parent_path().parent_path();
    fs::create_directories(dir_ / "subset/quick");
    for (const char* name : names) {
      const std::string file = std::string(name) + ".yaml";
      fs::copy_file(source / "experiments/specs/validate/quick" / file, dir_ / "subset/quick" / file);
    }
    return (dir_ / "subset").string();
  }

  fs::path dir_;
};

// (The clean quick set against the committed golden tables is the ctest `validate_quick`.)
TEST_F(ValidateCommandTest, InjectedAvarScaleErrorIsARegression) {
  const std::string specs = QuickSubset({"avar_bias_quick", "avar_error_bars_quick"});
  ASSERT_EQ(RunWithFault(specs, {.avar_scale = 1.03}), 1) << out_ << err_;
  const std::string& out = out_;
  EXPECT_NE(out.find("moved: avar_bias_quick point 0 avar_ratio/overlapping/m=1: "),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("moved: avar_error_bars_quick point 0 ratio/overlapping/m=1: "),
            std::string::npos)
      << out;
  EXPECT_NE(err_.find("allanlab validate: error: regression: "), std::string::npos) << err_;
}

// A 3 % error in every coefficient the drivers read or fit is caught by the coefficient tables'
// points (each method's N), not only by the Allan-variance ones.
TEST_F(ValidateCommandTest, InjectedCoefficientScaleErrorIsARegression) {
  const std::string specs =
      QuickSubset({"coefficient_recovery_quick", "record_length_quick", "seed_paper_quick"});
  ASSERT_EQ(RunWithFault(specs, {.coefficient_scale = 1.03}), 1) << out_ << err_;
  const std::string& out = out_;
  for (const char* moved : {"moved: coefficient_recovery_quick point 0 rel_err/gls/N: ",
                            "moved: coefficient_recovery_quick point 0 rel_err/wls/N: ",
                            "moved: record_length_quick point 1 rel_err/gls/N: ",
                            "moved: seed_paper_quick point 0 N_line/slope: "}) {
    EXPECT_NE(out.find(moved), std::string::npos) << moved << '\n' << out << err_;
  }
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
