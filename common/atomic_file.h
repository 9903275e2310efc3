#pragma once
// An output file that appears whole or not at all. Everything is written to a temporary in the
// destination's directory and renamed over the destination only by Commit(): a failed or
// interrupted run never leaves a half-written file, and a file that existed before survives it.
//
//   AtomicFile out;
//   if (!out.Open("trace.csv", &why)) return Fail(why);
//   out.stream() << ...;
//   if (!out.Commit(&why)) return Fail(why);   // the destructor discards an uncommitted file
//
// Commands writing several files open all of them first (so a bad path fails before any work is
// done) and commit them last, one after the other.
#include <fstream>
#include <string>
#include <string_view>

namespace allanlab {

class AtomicFile {
 public:
  AtomicFile() = default;
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  AtomicFile(AtomicFile&& other) noexcept;
  AtomicFile& operator=(AtomicFile&& other) noexcept;
  ~AtomicFile();  // Discard()s unless committed.

  // Creates an empty temporary "<path>.tmp.XXXXXX" next to `path` and opens stream() on it. Fails
  // (with the path and the system's reason in *why) if the directory is missing or not writable,
  // if `path` is a directory, or if `path` exists and is not writable. A symlink is followed, so
  // the file it points to is replaced, not the link. An existing `path` that is not a regular file
  // (/dev/null, /dev/stdout, a named pipe) is opened and written directly: there is nothing to
  // replace, and renaming over it would replace the device node itself.
  bool Open(const std::string& path, std::string* why);

  // Binary stream on the temporary; valid from a successful Open() until Commit() or Discard().
  std::ofstream& stream() { return stream_; }

  const std::string& path() const { return path_; }
  // The temporary's path, for writers that open the file themselves (e.g. a gnuplot child
  // process). They must have closed it before Commit().
  const std::string& temp_path() const { return temp_path_; }
  bool is_open() const { return !temp_path_.empty(); }

  // Closes the stream, fails if any write failed (disk full, ...), syncs the data to disk, gives
  // the file the permissions of the file it replaces (or those of a new file under the umask) and
  // renames it over path(). On failure the temporary is removed and path() is untouched.
  bool Commit(std::string* why);

  // Closes and removes the temporary; path() is untouched. Safe to call more than once.
  void Discard();

 private:
  std::string path_;       // destination (symlinks resolved)
  std::string temp_path_;  // empty when nothing is pending (path_ itself when direct_)
  bool direct_ = false;    // writing to a device or pipe in place (Open)
  std::ofstream stream_;
};

// Creates the missing directories above `path` (none for a bare file name).
bool CreateParentDirectories(const std::string& path, std::string* why);

// `content` written to `path` through an AtomicFile, missing parent directories created first.
bool WriteFileAtomically(const std::string& path, std::string_view content, std::string* why);

}  // namespace allanlab
