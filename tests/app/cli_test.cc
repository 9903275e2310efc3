// The top-level `allanlab` command as a user meets it: --version, --help and a mistyped command.
#include <gtest/gtest.h>

#include <string>

#include "tests/support/command_test.h"

namespace allanlab::app {
namespace {

class CliTest : public testing_support::CommandTest {
 protected:
  CliTest() : CommandTest("allanlab_cli_") {}
};

TEST_F(CliTest, VersionPrintsVersionCommitAndBuildType) {
  ASSERT_EQ(Run("--version"), 0) << Read("err.txt");
  const std::string out = Read("out.txt");
  EXPECT_EQ(out.rfind("allanlab " ALLANLAB_TEST_PROJECT_VERSION " (git ", 0), 0u) << out;
  EXPECT_EQ(out.substr(out.size() - 2), ")\n") << out;
  EXPECT_EQ(Read("err.txt"), "");
}

TEST_F(CliTest, HelpListsEveryCommand) {
  ASSERT_EQ(Run("--help"), 0) << Read("err.txt");
  const std::string out = Read("out.txt");
  for (const char* command : {"simulate", "avar", "fit", "diagnose", "diagnosis-benchmark", "sweep", "validate"}) {
    EXPECT_NE(out.find(std::string("  ") + command + " "), std::string::npos) << command << '\n' << out;
  }
  EXPECT_NE(out.find("--version"), std::string::npos) << out;
}

TEST_F(CliTest, UnknownCommandIsOneLineAndExitTwo) {
  EXPECT_EQ(Run("simulat"), 2);
  const std::string err = Read("err.txt");
  EXPECT_NE(err.find("unknown command 'simulat'"), std::string::npos) << err;
  EXPECT_EQ(err.find('\n'), err.size() - 1) << err;
}

}  // namespace
}  // namespace allanlab::app
