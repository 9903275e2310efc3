// `allanlab avar --stream` keeps its memory flat: the peak resident size of the process reading
// 10^7 samples is within a few MiB of the one reading 10^6 (the state is O(K log N)), while the
// in-memory command on 10^7 samples needs at least the 80 MB of the record, which shows that the
// measurement can tell the two apart.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

extern char** environ;

namespace allanlab::app {
namespace {

namespace fs = std::filesystem;

// Raw little-endian float32 noise (a cheap LCG: the content does not matter, only the size).
void WriteF32(const fs::path& path, std::int64_t n) {
  std::ofstream out(path, std::ios::binary);
  std::vector<char> block;
  std::uint64_t state = 12345;
  for (std::int64_t k = 0; k < n; ++k) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    const float v = static_cast<float>(static_cast<double>(state >> 40) / 16777216.0 - 0.5);
    const auto bits = std::bit_cast<std::uint32_t>(v);
    for (int i = 0; i < 4; ++i) block.push_back(static_cast<char>((bits >> (8 * i)) & 0xff));
    if (block.size() >= (1 << 20)) {
      out.write(block.data(), static_cast<std::streamsize>(block.size()));
      block.clear();
    }
  }
  out.write(block.data(), static_cast<std::streamsize>(block.size()));
}

// Runs the binary with `args` (stdout and stderr to /dev/null); returns the peak RSS in KiB, or
// -1 when the run failed.
long PeakKiB(const std::vector<std::string>& args) {
  std::vector<std::string> argv_text = {ALLANLAB_BINARY};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : argv_text) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) return -1;
  int status = 0;
  struct rusage usage {};
  if (::wait4(pid, &status, 0, &usage) != pid) return -1;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) return -1;
  return usage.ru_maxrss;
}

TEST(AvarStreamMemoryTest, PeakMemoryDoesNotGrowWithTheRecord) {
  // A folder of its own: two suites running at once (two worktrees) must not share the files.
  std::string pattern = (fs::path(::testing::TempDir()) / "avar_stream_memory_test.XXXXXX").string();
  ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
  const fs::path dir = pattern;
  const fs::path small = dir / "1e6.f32", large = dir / "1e7.f32";
  WriteF32(small, 1000000);
  WriteF32(large, 10000000);
  const std::vector<std::string> stream = {"--format", "f32", "--rate", "100", "--units", "deg/s",
                                           "--stream"};
  auto with = [](std::vector<std::string> v, const fs::path& file) {
    v.insert(v.begin(), {"avar", file.string()});
    return v;
  };
  const long stream_small = PeakKiB(with(stream, small));
  const long stream_large = PeakKiB(with(stream, large));
  const long memory_large =
      PeakKiB(with({"--format", "f32", "--rate", "100", "--units", "deg/s", "--ci", "none"}, large));
  fs::remove_all(dir);
  ASSERT_GT(stream_small, 0);
  ASSERT_GT(stream_large, 0);
  ASSERT_GT(memory_large, 0);
  std::cout << "peak RSS: --stream 1e6 " << stream_small << " KiB, --stream 1e7 " << stream_large
            << " KiB, in memory 1e7 " << memory_large << " KiB\n";
  // What the check must catch is growth with the record: holding the 9e6 more samples would add at
  // least 34 MiB (4 bytes each), so a quarter of that, 8 MiB, is the bound. The state itself adds
  // about 1.5 MiB (3 more octaves of at most 2 * 16384 + 1 16-byte entries); the whole process
  // adds more: 3.5 MiB, and 4.0 MiB once the second thread makes the next block's sums
  // (its own allocations), which a 4 MiB bound then failed under load.
  EXPECT_LT(stream_large - stream_small, 8192) << "streaming memory grew with the record";
  // In memory: one double per sample (8e7 bytes = 78125 KiB; the phase is built in the record's
  // own storage), less the streaming state it does not need.
  EXPECT_GT(memory_large, stream_large + 78125 * 4 / 5)
      << "the in-memory run should hold about 8e7 bytes more";
}

}  // namespace
}  // namespace allanlab::app
