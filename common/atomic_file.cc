#include "common/atomic_file.h"

#include <fcntl.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <utility>
#include <vector>

namespace allanlab {
namespace {

namespace fs = std::filesystem;

bool Fail(std::string* why, const std::string& message) {
  if (why) *why = message;
  return false;
}

std::string SystemError(int error) { return std::strerror(error); }

// The mode open(2) would give a new file, 0666 minus the umask. umask(2) can only be read by
// setting it, so it is read once and put straight back.
mode_t NewFileMode() {
  static const mode_t mode = [] {
    const mode_t mask = ::umask(0);
    ::umask(mask);
    return static_cast<mode_t>(0666 & ~mask);
  }();
  return mode;
}

}  // namespace

AtomicFile::AtomicFile(AtomicFile&& other) noexcept
    : path_(std::move(other.path_)),
      temp_path_(std::exchange(other.temp_path_, std::string())),
      direct_(std::exchange(other.direct_, false)),
      stream_(std::move(other.stream_)) {}

AtomicFile& AtomicFile::operator=(AtomicFile&& other) noexcept {
  if (this != &other) {
    Discard();
    path_ = std::move(other.path_);
    temp_path_ = std::exchange(other.temp_path_, std::string());
    direct_ = std::exchange(other.direct_, false);
    stream_ = std::move(other.stream_);
  }
  return *this;
}

AtomicFile::~AtomicFile() { Discard(); }

bool AtomicFile::Open(const std::string& path, std::string* why) {
  Discard();
  if (path.empty()) return Fail(why, "empty output path");
  struct stat st;
  if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode)) {
    // A device, FIFO or socket (/dev/null, /dev/stdout, a named pipe): written where it is. A
    // rename would replace the device node itself with a regular file (as root, /dev/null).
    stream_.open(path, std::ios::binary);
    if (!stream_) return Fail(why, "cannot write " + path + ": " + SystemError(errno));
    path_ = temp_path_ = path;
    direct_ = true;
    return true;
  }
  std::error_code ec;
  std::string target = path;
  if (fs::is_symlink(path, ec)) {
    const fs::path resolved = fs::weakly_canonical(path, ec);
    if (ec) return Fail(why, "cannot resolve symlink " + path + ": " + ec.message());
    target = resolved.string();
  }
  if (::stat(target.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) return Fail(why, "cannot write " + path + ": it is a directory");
    // rename(2) would replace a read-only file; honour the user's protection instead.
    if (::access(target.c_str(), W_OK) != 0) {
      return Fail(why, "cannot write " + path + ": " + SystemError(errno));
    }
  }
  std::vector<char> templ(target.begin(), target.end());
  const std::string suffix = ".tmp.XXXXXX";
  templ.insert(templ.end(), suffix.begin(), suffix.end());
  templ.push_back('\0');
  const int fd = ::mkstemp(templ.data());
  if (fd < 0) return Fail(why, "cannot write " + path + ": " + SystemError(errno));
  ::close(fd);
  temp_path_ = templ.data();
  path_ = target;
  stream_.open(temp_path_, std::ios::binary | std::ios::trunc);
  if (!stream_) {
    const int error = errno;
    Discard();
    return Fail(why, "cannot write " + path + ": " + SystemError(error));
  }
  return true;
}

bool AtomicFile::Commit(std::string* why) {
  if (temp_path_.empty()) return Fail(why, "internal error: commit of a file that is not open");
  if (stream_.is_open()) {
    stream_.flush();
    stream_.close();
  }
  if (stream_.fail()) {
    Discard();
    return Fail(why, "error writing " + path_ + (direct_ ? "" : " (disk full?)"));
  }
  if (direct_) {
    temp_path_.clear();
    direct_ = false;
    return true;
  }
  // Sync before the rename so that a crash cannot leave a complete name on incomplete data.
  const int fd = ::open(temp_path_.c_str(), O_RDONLY);
  if (fd < 0 || ::fsync(fd) != 0) {
    const int error = errno;
    if (fd >= 0) ::close(fd);
    Discard();
    return Fail(why, "error writing " + path_ + ": " + SystemError(error));
  }
  ::close(fd);
  struct stat st;
  const mode_t mode = ::stat(path_.c_str(), &st) == 0 ? (st.st_mode & 07777) : NewFileMode();
  if (::chmod(temp_path_.c_str(), mode) != 0 || ::rename(temp_path_.c_str(), path_.c_str()) != 0) {
    const int error = errno;
    Discard();
    return Fail(why, "cannot replace " + path_ + ": " + SystemError(error));
  }
  temp_path_.clear();
  return true;
}

void AtomicFile::Discard() {
  if (stream_.is_open()) stream_.close();
  stream_.clear();
  if (!temp_path_.empty() && !direct_) std::remove(temp_path_.c_str());
  temp_path_.clear();
  direct_ = false;
}

bool CreateParentDirectories(const std::string& path, std::string* why) {
  const fs::path parent = fs::path(path).parent_path();
  if (parent.empty()) return true;
  std::error_code error;
  fs::create_directories(parent, error);
  if (error) return Fail(why, "cannot create directory " + parent.string() + ": " + error.message());
  return true;
}

bool WriteFileAtomically(const std::string& path, std::string_view content, std::string* why) {
  AtomicFile file;
  if (!CreateParentDirectories(path, why) || !file.Open(path, why)) return false;
  file.stream().write(content.data(), static_cast<std::streamsize>(content.size()));
  return file.Commit(why);
}

}  // namespace allanlab
