#include "app/input/byte_source.h"

#include <fcntl.h>
#include <lzma.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <cerrno>
#include <cstring>
#include <vector>

namespace allanlab::app {
namespace {

constexpr std::size_t kInputChunk = 1 << 16;
// xz -9 needs a 64 MiB dictionary; anything asking for more is not a file we wrote or expect.
constexpr std::uint64_t kXzMemoryLimit = std::uint64_t{256} << 20;

bool Fail(std::string* why, std::string message) {
  if (why) *why = std::move(message);
  return false;
}

// The raw file with one input buffer that the decoders consume in place.
class RawFile {
 public:
  explicit RawFile(int fd, std::string path) : fd_(fd), path_(std::move(path)) {
    buffer_.resize(kInputChunk);
  }
  ~RawFile() { ::close(fd_); }
  RawFile(const RawFile&) = delete;
  RawFile& operator=(const RawFile&) = delete;

  // Refills the buffer when it is empty; false on a read error. eof() after a refill that read
  // nothing.
  bool Fill(std::string* why) {
    if (begin_ < end_ || eof_) return true;
    while (true) {
      const ssize_t n = ::read(fd_, buffer_.data(), buffer_.size());
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) return Fail(why, "cannot read " + path_ + ": " + std::strerror(errno));
      begin_ = 0;
      end_ = static_cast<std::size_t>(n);
      eof_ = n == 0;
      return true;
    }
  }
  // Reads until at least `n` bytes are buffered or the input ends (only at the start: the
  // buffer holds 64 KiB).
  bool FillAtLeast(std::size_t n, std::string* why) {
    while (size() < n && !eof_) {
      const ssize_t got = ::read(fd_, buffer_.data() + end_, buffer_.size() - end_);
      if (got < 0 && errno == EINTR) continue;
      if (got < 0) return Fail(why, "cannot read " + path_ + ": " + std::strerror(errno));
      end_ += static_cast<std::size_t>(got);
      eof_ = got == 0;
    }
    return true;
  }
  // Reads straight into `out` when nothing is buffered (no copy through the buffer); false on a
  // read error. *got == 0 at the end of the input.
  bool ReadInto(std::span<char> out, std::size_t* got, std::string* why) {
    *got = 0;
    if (begin_ < end_ || eof_) return true;
    while (true) {
      const ssize_t n = ::read(fd_, out.data(), out.size());
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) return Fail(why, "cannot read " + path_ + ": " + std::strerror(errno));
      eof_ = n == 0;
      *got = static_cast<std::size_t>(n);
      return true;
    }
  }
  const unsigned char* data() const {
    return reinterpret_cast<const unsigned char*>(buffer_.data()) + begin_;
  }
  std::size_t size() const { return end_ - begin_; }
  void Consume(std::size_t n) { begin_ += n; }
  bool eof() const { return eof_ && begin_ == end_; }
  const std::string& path() const { return path_; }

 private:
  int fd_;
  std::string path_;
  std::vector<char> buffer_;
  std::size_t begin_ = 0, end_ = 0;
  bool eof_ = false;
};

class PlainSource : public ByteSource {
 public:
  explicit PlainSource(std::unique_ptr<RawFile> file) : file_(std::move(file)) {}
  bool Read(std::span<char> out, std::size_t* got, std::string* why) override {
    *got = 0;
    // A large request with nothing buffered (every read after the format check's first bytes):
    // straight from the file into `out`.
    if (file_->size() == 0 && out.size() >= kInputChunk) return file_->ReadInto(out, got, why);
    if (!file_->Fill(why)) return false;
    const std::size_t n = std::min(out.size(), file_->size());
    std::memcpy(out.data(), file_->data(), n);
    file_->Consume(n);
    *got = n;
    return true;
  }
  Compression compression() const override { return Compression::kNone; }

 private:
  std::unique_ptr<RawFile> file_;
};

class GzipSource : public ByteSource {
 public:
  explicit GzipSource(std::unique_ptr<RawFile> file) : file_(std::move(file)) {}
  ~GzipSource() override {
    if (initialized_) inflateEnd(&z_);
  }
  bool Init(std::string* why) {
    // 16 + MAX_WBITS: gzip wrapper only, so a stray zlib stream is reported as corrupt.
    if (inflateInit2(&z_, 16 + MAX_WBITS) != Z_OK) {
      return Fail(why, "cannot start the gzip decoder for " + file_->path());
    }
    initialized_ = true;
    return true;
  }
  bool Read(std::span<char> out, std::size_t* got, std::string* why) override {
    *got = 0;
    if (done_) return true;
    z_.next_out = reinterpret_cast<Bytef*>(out.data());
    z_.avail_out = static_cast<uInt>(out.size());
    while (z_.avail_out == out.size()) {
      if (!file_->Fill(why)) return false;
      if (file_->eof()) {
        // Between members a clean end is fine; inside one the file was cut short.
        if (in_member_) return Fail(why, file_->path() + ": truncated gzip data");
        done_ = true;
        break;
      }
      z_.next_in = const_cast<Bytef*>(file_->data());
      z_.avail_in = static_cast<uInt>(file_->size());
      const int rc = inflate(&z_, Z_NO_FLUSH);
      file_->Consume(file_->size() - z_.avail_in);
      in_member_ = true;
      if (rc == Z_STREAM_END) {
        // gzip allows concatenated members (cat a.gz b.gz): start the next one.
        in_member_ = false;
        inflateReset(&z_);
      } else if (rc != Z_OK && rc != Z_BUF_ERROR) {
        return Fail(why, file_->path() + ": corrupt gzip data (" +
                             (z_.msg ? std::string(z_.msg) : "zlib error " + std::to_string(rc)) +
                             ")");
      }
    }
    *got = out.size() - z_.avail_out;
    return true;
  }
  Compression compression() const override { return Compression::kGzip; }

 private:
  std::unique_ptr<RawFile> file_;
  z_stream z_{};
  bool initialized_ = false;
  bool in_member_ = false;
  bool done_ = false;
};

std::string LzmaMessage(lzma_ret rc) {
  switch (rc) {
    case LZMA_MEM_ERROR:
      return "out of memory";
    case LZMA_MEMLIMIT_ERROR:
      return "needs more than 256 MiB of decoder memory";
    case LZMA_FORMAT_ERROR:
      return "not xz data";
    case LZMA_OPTIONS_ERROR:
      return "unsupported xz options";
    case LZMA_DATA_ERROR:
      return "corrupt xz data";
    case LZMA_BUF_ERROR:
      return "truncated xz data";
    default:
      return "xz decoder error " + std::to_string(static_cast<int>(rc));
  }
}

class XzSource : public ByteSource {
 public:
  explicit XzSource(std::unique_ptr<RawFile> file) : file_(std::move(file)) {}
  ~XzSource() override { lzma_end(&strm_); }
  bool Init(std::string* why) {
    // CONCATENATED: `cat a.xz b.xz` is one stream of data, as xz(1) reads it.
    const lzma_ret rc = lzma_stream_decoder(&strm_, kXzMemoryLimit, LZMA_CONCATENATED);
    if (rc != LZMA_OK) return Fail(why, file_->path() + ": " + LzmaMessage(rc));
    return true;
  }
  bool Read(std::span<char> out, std::size_t* got, std::string* why) override {
    *got = 0;
    if (done_) return true;
    strm_.next_out = reinterpret_cast<uint8_t*>(out.data());
    strm_.avail_out = out.size();
    while (strm_.avail_out == out.size()) {
      if (!file_->Fill(why)) return false;
      const lzma_action action = file_->eof() ? LZMA_FINISH : LZMA_RUN;
      strm_.next_in = file_->data();
      strm_.avail_in = file_->size();
      const lzma_ret rc = lzma_code(&strm_, action);
      file_->Consume(file_->size() - strm_.avail_in);
      if (rc == LZMA_STREAM_END) {
        done_ = true;
        break;
      }
      if (rc != LZMA_OK) return Fail(why, file_->path() + ": " + LzmaMessage(rc));
    }
    *got = out.size() - strm_.avail_out;
    return true;
  }
  Compression compression() const override { return Compression::kXz; }

 private:
  std::unique_ptr<RawFile> file_;
  lzma_stream strm_ = LZMA_STREAM_INIT;
  bool done_ = false;
};

}  // namespace

std::string_view CompressionName(Compression compression) {
  switch (compression) {
    case Compression::kNone:
      return "none";
    case Compression::kGzip:
      return "gzip";
    case Compression::kXz:
      return "xz";
  }
  return "?";
}

bool OpenByteSource(const std::string& path, std::unique_ptr<ByteSource>* source,
                    std::string* why) {
  // "-": standard input, duplicated so that closing the source leaves fd 0 alone.
  const bool stdin_path = path == "-";
  const int fd = stdin_path ? ::fcntl(0, F_DUPFD_CLOEXEC, 0) : ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    return Fail(why, "cannot open " + std::string(stdin_path ? "stdin" : path) + ": " +
                         std::strerror(errno));
  }
  struct stat st;
  if (::fstat(fd, &st) == 0 && S_ISDIR(st.st_mode)) {
    ::close(fd);
    return Fail(why, "cannot open " + path + ": it is a directory");
  }
  auto file = std::make_unique<RawFile>(fd, stdin_path ? "stdin" : path);
  // A pipe may deliver fewer bytes per read than the 6-byte magic: read until it is whole.
  if (!file->FillAtLeast(6, why)) return false;
  static constexpr unsigned char kGzipMagic[] = {0x1f, 0x8b};
  static constexpr unsigned char kXzMagic[] = {0xfd, '7', 'z', 'X', 'Z', 0x00};
  const auto starts_with = [&](const unsigned char* magic, std::size_t n) {
    return file->size() >= n && std::memcmp(file->data(), magic, n) == 0;
  };
  if (starts_with(kXzMagic, sizeof kXzMagic)) {
    auto xz = std::make_unique<XzSource>(std::move(file));
    if (!xz->Init(why)) return false;
    *source = std::move(xz);
  } else if (starts_with(kGzipMagic, sizeof kGzipMagic)) {
    auto gz = std::make_unique<GzipSource>(std::move(file));
    if (!gz->Init(why)) return false;
    *source = std::move(gz);
  } else {
    *source = std::make_unique<PlainSource>(std::move(file));
  }
  return true;
}

}  // namespace allanlab::app
