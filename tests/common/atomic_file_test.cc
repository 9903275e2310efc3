#include "common/atomic_file.h"

#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/support/read_file.h"

namespace allanlab {
namespace {

namespace fs = std::filesystem;

using testing_support::ReadAll;

void WriteAll(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

class AtomicFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string templ = (fs::path(::testing::TempDir()) / "atomic_file_test.XXXXXX").string();
    ASSERT_NE(::mkdtemp(templ.data()), nullptr);
    dir_ = templ;
  }
  void TearDown() override { fs::remove_all(dir_); }
  // Number of entries in the directory: a leftover temporary shows up here.
  int Entries() const {
    int n = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir_)) ++n;
    return n;
  }
  fs::path dir_;
};

TEST_F(AtomicFileTest, CommitCreatesTheFileAndLeavesNoTemporary) {
  AtomicFile file;
  std::string why;
  ASSERT_TRUE(file.Open((dir_ / "out.txt").string(), &why)) << why;
  file.stream() << "hello\n";
  EXPECT_FALSE(fs::exists(dir_ / "out.txt")) << "visible before Commit()";
  ASSERT_TRUE(file.Commit(&why)) << why;
  EXPECT_EQ(ReadAll(dir_ / "out.txt"), "hello\n");
  EXPECT_EQ(Entries(), 1);
}

TEST_F(AtomicFileTest, UncommittedFileLeavesTheOldContentAndNoTemporary) {
  WriteAll(dir_ / "out.txt", "precious\n");
  {
    AtomicFile file;
    std::string why;
    ASSERT_TRUE(file.Open((dir_ / "out.txt").string(), &why)) << why;
    file.stream() << "half a";
  }
  EXPECT_EQ(ReadAll(dir_ / "out.txt"), "precious\n");
  EXPECT_EQ(Entries(), 1);
}

TEST_F(AtomicFileTest, CommitReplacesAndKeepsTheOldPermissions) {
  WriteAll(dir_ / "out.txt", "old\n");
  fs::permissions(dir_ / "out.txt", fs::perms(0640));
  AtomicFile file;
  std::string why;
  ASSERT_TRUE(file.Open((dir_ / "out.txt").string(), &why)) << why;
  file.stream() << "new\n";
  ASSERT_TRUE(file.Commit(&why)) << why;
  EXPECT_EQ(ReadAll(dir_ / "out.txt"), "new\n");
  EXPECT_EQ(fs::status(dir_ / "out.txt").permissions(), fs::perms(0640));
}

TEST_F(AtomicFileTest, NewFileGetsTheUmaskModeNotTheTemporarys0600) {
  const mode_t mask = ::umask(022);
  AtomicFile file;
  std::string why;
  ASSERT_TRUE(file.Open((dir_ / "out.txt").string(), &why)) << why;
  ASSERT_TRUE(file.Commit(&why)) << why;
  ::umask(mask);
  EXPECT_EQ(fs::status(dir_ / "out.txt").permissions(), fs::perms(0644));
}

TEST_F(AtomicFileTest, MissingDirectoryFailsWithThePath) {
  AtomicFile file;
  std::string why;
  const std::string path = (dir_ / "no_such_dir" / "out.txt").string();
  EXPECT_FALSE(file.Open(path, &why));
  EXPECT_NE(why.find(path), std::string::npos) << why;
  EXPECT_EQ(Entries(), 0);
}

TEST_F(AtomicFileTest, DirectoryAsTargetFails) {
  fs::create_directory(dir_ / "sub");
  AtomicFile file;
  std::string why;
  EXPECT_FALSE(file.Open((dir_ / "sub").string(), &why));
  EXPECT_NE(why.find("directory"), std::string::npos) << why;
  EXPECT_EQ(Entries(), 1);
}

TEST_F(AtomicFileTest, SymlinkIsFollowed) {
  WriteAll(dir_ / "target.txt", "old\n");
  fs::create_symlink("target.txt", dir_ / "link.txt");
  AtomicFile file;
  std::string why;
  ASSERT_TRUE(file.Open((dir_ / "link.txt").string(), &why)) << why;
  file.stream() << "new\n";
  ASSERT_TRUE(file.Commit(&why)) << why;
  EXPECT_TRUE(fs::is_symlink(dir_ / "link.txt"));
  EXPECT_EQ(ReadAll(dir_ / "target.txt"), "new\n");
}

TEST_F(AtomicFileTest, MovedFromFileOwnsNothing) {
  AtomicFile a;
  std::string why;
  ASSERT_TRUE(a.Open((dir_ / "out.txt").string(), &why)) << why;
  AtomicFile b = std::move(a);
  EXPECT_FALSE(a.is_open());  // NOLINT(bugprone-use-after-move): checking the moved-from state
  b.stream() << "x";
  ASSERT_TRUE(b.Commit(&why)) << why;
  EXPECT_EQ(ReadAll(dir_ / "out.txt"), "x");
}

TEST_F(AtomicFileTest, CommitWithoutOpenFails) {
  AtomicFile file;
  std::string why;
  EXPECT_FALSE(file.Commit(&why));
  EXPECT_FALSE(why.empty());
}

// A device (/dev/null, /dev/stdout, a named pipe: not a regular file) is written where it is, not
// replaced: as root, `--json /dev/null` had renamed a regular file over the device node /dev/null
// (and without root the temporary could not be made in /dev, so the write failed).
TEST_F(AtomicFileTest, ADeviceIsWrittenInPlaceNotReplaced) {
  if (!fs::is_character_file("/dev/null")) GTEST_SKIP() << "/dev/null is not a device on this machine";
  std::string why;
  AtomicFile null;
  ASSERT_TRUE(null.Open("/dev/null", &why)) << why;
  EXPECT_EQ(null.path(), "/dev/null");
  null.stream() << "discarded";
  null.Discard();
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  ASSERT_TRUE(null.Open("/dev/null", &why)) << why;
  null.stream() << "written";
  EXPECT_TRUE(null.Commit(&why)) << why;
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
}

}  // namespace
}  // namespace allanlab
