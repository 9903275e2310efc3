#pragma once
// A file read as a stream of bytes, decompressed on the fly when it is gzip (zlib) or xz
// (liblzma). The format is recognised by its magic bytes, not by the file name, so `data.csv`
// that is really gzip still reads, and `data.csv.gz` that is plain text is not mangled.
//
// Memory: one fixed input buffer and the decoder's own state (xz: the dictionary, at most 64 MiB
// for `xz -9`, decoder memory limit below); the decompressed text is never held whole.
#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <string_view>

namespace allanlab::app {

enum class Compression { kNone, kGzip, kXz };

// "none", "gzip", "xz": for messages and provenance.
std::string_view CompressionName(Compression compression);

class ByteSource {
 public:
  virtual ~ByteSource() = default;
  // Fills up to out.size() bytes and sets *got; *got == 0 with true means end of data. On a read
  // error or corrupt/truncated compressed data returns false with the reason (naming the file).
  virtual bool Read(std::span<char> out, std::size_t* got, std::string* why) = 0;
  virtual Compression compression() const = 0;
};

// Opens `path`; "-" is standard input (read once, as a stream; messages call it "stdin"). Fails with "cannot open PATH: <reason>" when the file is
// missing, unreadable or a directory.
bool OpenByteSource(const std::string& path, std::unique_ptr<ByteSource>* source, std::string* why);

}  // namespace allanlab::app
