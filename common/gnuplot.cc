#include "common/gnuplot.h"

#include <fcntl.h>
#include <spawn.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string_view>
#include <vector>

extern char** environ;

namespace allanlab {
namespace {

constexpr const char* kGnuplot = "gnuplot";
constexpr const char* kInstallHint =
    "gnuplot not found on PATH; install it (e.g. apt-get install gnuplot-nox) or run without the "
    "plot options";

bool Fail(std::string* why, const std::string& message) {
  if (why) *why = message;
  return false;
}

// A scratch file in the system temp directory, removed when it goes out of scope.
class ScratchFile {
 public:
  bool Create(std::string* why) {
    std::error_code ec;
    std::string templ = (std::filesystem::temp_directory_path(ec) / "allanlab-plot.XXXXXX").string();
    if (ec) templ = "/tmp/allanlab-plot.XXXXXX";
    std::vector<char> buffer(templ.begin(), templ.end());
    buffer.push_back('\0');
    fd_ = ::mkstemp(buffer.data());
    if (fd_ < 0) return Fail(why, "cannot create a temporary file: " + std::string(std::strerror(errno)));
    path_ = buffer.data();
    return true;
  }
  ~ScratchFile() {
    if (fd_ >= 0) ::close(fd_);
    if (!path_.empty()) std::remove(path_.c_str());
  }
  const std::string& path() const { return path_; }
  int fd() const { return fd_; }

 private:
  std::string path_;
  int fd_ = -1;
};

// The first line of gnuplot's stderr that says what went wrong, for a one-line message.
std::string FirstErrorLine(const std::string& log_path) {
  std::ifstream log(log_path);
  std::string line, first;
  while (std::getline(log, line)) {
    if (line.find_first_not_of(" \t^") == std::string::npos) continue;
    if (first.empty()) first = line;
    if (line.find("rror") != std::string::npos) return line;
  }
  return first.empty() ? "no message" : first;
}

}  // namespace

bool FindGnuplot(std::string* why) {
  const char* path = std::getenv("PATH");
  std::string_view dirs = path ? path : "";
  while (true) {
    const std::size_t colon = dirs.find(':');
    // An empty PATH entry means the current directory.
    const std::filesystem::path dir = colon == 0 || dirs.empty() ? std::filesystem::path(".")
                                                                 : std::filesystem::path(dirs.substr(0, colon));
    const std::string candidate = (dir / kGnuplot).string();
    struct stat st;
    if (::stat(candidate.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(candidate.c_str(), X_OK) == 0) {
      return true;
    }
    if (colon == std::string_view::npos) break;
    dirs.remove_prefix(colon + 1);
  }
  return Fail(why, kInstallHint);
}

std::string GnuplotQuoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\'') {
      out += "''";
    } else {
      out += c;
    }
  }
  out += "'";
  return out;
}

bool RunGnuplot(const std::string& script_text, std::string* why) {
  ScratchFile script, log;
  if (!script.Create(why) || !log.Create(why)) return false;
  if (::write(script.fd(), script_text.data(), script_text.size()) != static_cast<ssize_t>(script_text.size())) {
    return Fail(why, "cannot write the gnuplot script: " + std::string(std::strerror(errno)));
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, log.fd(), STDERR_FILENO);
  std::string script_path = script.path();
  std::string program = kGnuplot;
  char* argv[] = {program.data(), script_path.data(), nullptr};
  pid_t pid = 0;
  const int spawn_error = ::posix_spawnp(&pid, kGnuplot, &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawn_error == ENOENT) return Fail(why, kInstallHint);
  if (spawn_error != 0) return Fail(why, "cannot run gnuplot: " + std::string(std::strerror(spawn_error)));
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return Fail(why, "lost the gnuplot process: " + std::string(std::strerror(errno)));
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    // posix_spawnp may report a failed exec only through exit status 127.
    if (WIFEXITED(status) && WEXITSTATUS(status) == 127) return Fail(why, kInstallHint);
    return Fail(why, "gnuplot failed: " + FirstErrorLine(log.path()));
  }
  return true;
}

bool GnuplotWroteImage(const std::string& path, std::string* why) {
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) return Fail(why, "gnuplot wrote no image at " + path);
  // A device or pipe (--plot /dev/null) has no size to check: gnuplot's exit status is the word.
  if (S_ISREG(st.st_mode) && st.st_size == 0) return Fail(why, "gnuplot wrote no image at " + path);
  return true;
}

}  // namespace allanlab
