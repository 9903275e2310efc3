#pragma once
// A fixture for tests that run the built `allanlab` binary: a fresh scratch directory per test
// (removed afterwards), the command's stdout and stderr captured to out.txt and err.txt there.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>

#include "tests/support/read_file.h"

namespace allanlab::testing_support {

// The text without its '#' lines: a table without its provenance comments (the date and the
// command line differ between runs that must agree).
inline std::string WithoutCommentLines(const std::string& text) {
  std::istringstream in(text);
  std::string body;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind('#', 0) == 0) continue;
    body += line;
    body += '\n';
  }
  return body;
}

class CommandTest : public ::testing::Test {
 protected:
  // `prefix` names the scratch directory (<tmp>/<prefix><test name>_<pid>); `command` is put before
  // every Run's arguments (e.g. "diagnose"), empty for none.
  explicit CommandTest(std::string prefix, std::string command = "")
      : prefix_(std::move(prefix)), command_(std::move(command)) {}

  void SetUp() override {
    // The process id keeps two suites running at once on one machine (two build trees) out of
    // each other's scratch directories: one's SetUp had removed the other's running benchmark.
    dir_ = std::filesystem::temp_directory_path() / prefix_;
    dir_ += ::testing::UnitTest::GetInstance()->current_test_info()->name();
    dir_ += "_";
    dir_ += std::to_string(::getpid());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // Runs `allanlab [command] args` through the shell; returns its exit code (-1 if it did not
  // exit normally). A stream, not a '+' chain: GCC 12 warns falsely (-Wrestrict) on those.
  int Run(const std::string& args) {
    std::ostringstream line;
    line << ALLANLAB_BINARY << ' ' << command_ << (command_.empty() ? "" : " ") << args << " > '"
         << (dir_ / "out.txt").string() << "' 2> '" << (dir_ / "err.txt").string() << "'";
    const int status = std::system(line.str().c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  std::string Read(const std::string& name) const { return ReadAll(dir_ / name); }
  // The path of `name` in the scratch directory, single-quoted for the shell.
  std::string Path(const std::string& name) const {
    std::ostringstream quoted;
    quoted << '\'' << (dir_ / name).string() << '\'';
    return quoted.str();
  }

  std::filesystem::path dir_;

 private:
  std::string prefix_;
  std::string command_;
};

}  // namespace allanlab::testing_support
