#pragma once
// A regular file's bytes mapped read-only. A raw record read this way is used where it lies in
// the page cache: no record-sized buffer is zeroed by the kernel and filled by copying (on 1e7
// float64 samples, 80 MB of each), which cost more than the Allan pass itself.
#include <cstddef>
#include <span>
#include <string>

namespace allanlab::app {

class MappedFile {
 public:
  MappedFile() = default;
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  // Maps `path` when it is a non-empty regular file; false otherwise (standard input, a pipe, a
  // missing or unreadable file, or a failed mapping), with nothing mapped and no message: such a
  // file is read as a stream, which reports what is wrong with it. A file that grows meanwhile
  // is read as it was; one that another process truncates meanwhile faults (SIGBUS) when the
  // lost pages are read, where a stream would have read the shorter file.
  bool Map(const std::string& path);
  std::span<const char> bytes() const { return {static_cast<const char*>(data_), size_}; }

 private:
  void* data_ = nullptr;
  std::size_t size_ = 0;
};

}  // namespace allanlab::app
