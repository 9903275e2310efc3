#include "experiments/checkpoint_store.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <string_view>

#include "experiments/row_codec.h"

namespace allanlab::experiments {
namespace {

constexpr std::string_view kMagic = "allanlab checkpoint v1\n";
constexpr std::uint32_t kRecordMagic = 0xA11A4B01u;

std::string SystemError(const std::string& what, const std::string& path) {
  std::string text = what;
  text += ' ';
  text += path;
  text += ": ";
  text += std::strerror(errno);
  return text;
}

bool WriteAll(int fd, const unsigned char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    data += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

template <typename T>
void Put(const T& value, std::vector<unsigned char>* out) {
  const auto* p = reinterpret_cast<const unsigned char*>(&value);
  out->insert(out->end(), p, p + sizeof(T));
}

std::vector<unsigned char> Header(std::uint64_t spec_hash, const std::string& driver) {
  std::vector<unsigned char> header;
  for (char c : kMagic) header.push_back(static_cast<unsigned char>(c));
  Put(spec_hash, &header);
  Put<std::uint32_t>(static_cast<std::uint32_t>(driver.size()), &header);
  header.insert(header.end(), driver.begin(), driver.end());
  return header;
}

bool ReadFile(const std::string& path, std::vector<unsigned char>* bytes, std::string* why) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    *why = SystemError("cannot open checkpoint", path);
    return false;
  }
  unsigned char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      *why = SystemError("cannot read checkpoint", path);
      ::close(fd);
      return false;
    }
    if (n == 0) break;
    bytes->insert(bytes->end(), buffer, buffer + n);
  }
  ::close(fd);
  return true;
}

}  // namespace

CheckpointStore::~CheckpointStore() { Close(); }

void CheckpointStore::Close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

bool CheckpointStore::Create(const std::string& path, std::uint64_t spec_hash,
                             const std::string& driver, std::string* why) {
  Close();
  struct stat st;
  if (::stat(path.c_str(), &st) == 0) {
    *why = "checkpoint " + path +
           " already exists (an interrupted run?): pass --resume to continue it, or delete it";
    return false;
  }
  const std::string temp = path + ".new";
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) {
    *why = SystemError("cannot create checkpoint", temp);
    return false;
  }
  const std::vector<unsigned char> header = Header(spec_hash, driver);
  if (!WriteAll(fd, header.data(), header.size()) || ::fsync(fd) != 0) {
    *why = SystemError("cannot write checkpoint", temp);
    ::close(fd);
    ::unlink(temp.c_str());
    return false;
  }
  ::close(fd);
  if (::rename(temp.c_str(), path.c_str()) != 0) {
    *why = SystemError("cannot rename checkpoint into", path);
    ::unlink(temp.c_str());
    return false;
  }
  fd_ = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (fd_ < 0) {
    *why = SystemError("cannot open checkpoint", path);
    return false;
  }
  path_ = path;
  return true;
}

bool CheckpointStore::Resume(const std::string& path, std::uint64_t spec_hash,
                             const std::string& driver, std::vector<TrialRow>* rows,
                             std::string* why) {
  Close();
  std::vector<unsigned char> bytes;
  if (!ReadFile(path, &bytes, why)) return false;
  const std::vector<unsigned char> header = Header(spec_hash, driver);
  const std::size_t magic_size = kMagic.size();
  if (bytes.size() < magic_size || std::memcmp(bytes.data(), kMagic.data(), magic_size) != 0) {
    *why = "checkpoint " + path + " is not an allanlab checkpoint";
    return false;
  }
  if (bytes.size() < header.size() || std::memcmp(bytes.data(), header.data(), header.size()) != 0) {
    std::uint64_t hash = 0;
    if (bytes.size() >= magic_size + sizeof hash) {
      std::memcpy(&hash, bytes.data() + magic_size, sizeof hash);
    }
    std::ostringstream os;
    os << "checkpoint " << path << " belongs to another sweep (spec hash " << std::hex << hash
       << ", this spec " << spec_hash << ", or another driver): delete it or drop --resume";
    *why = os.str();
    return false;
  }
  // Records: u32 magic, u64 payload size, payload, u64 FNV-1a of the payload.
  std::size_t pos = header.size();
  std::vector<TrialRow> loaded;
  for (;;) {
    constexpr std::size_t kFixed = sizeof(std::uint32_t) + 2 * sizeof(std::uint64_t);
    if (bytes.size() - pos < kFixed) break;
    std::uint32_t magic = 0;
    std::uint64_t size = 0;
    std::memcpy(&magic, bytes.data() + pos, sizeof magic);
    std::memcpy(&size, bytes.data() + pos + sizeof magic, sizeof size);
    if (magic != kRecordMagic || size > bytes.size() - pos - kFixed) break;
    const unsigned char* payload = bytes.data() + pos + sizeof magic + sizeof size;
    std::uint64_t checksum = 0;
    std::memcpy(&checksum, payload + size, sizeof checksum);
    const std::span<const unsigned char> span(payload, size);
    std::vector<TrialRow> batch;
    if (checksum != Fnv1a64(span) || !DecodeRows(span, &batch)) break;
    for (TrialRow& row : batch) loaded.push_back(std::move(row));
    pos += kFixed + size;
  }
  // Drop a torn tail so the next record follows the last intact one.
  if (pos < bytes.size() && ::truncate(path.c_str(), static_cast<off_t>(pos)) != 0) {
    *why = SystemError("cannot truncate the torn end of checkpoint", path);
    return false;
  }
  fd_ = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (fd_ < 0) {
    *why = SystemError("cannot open checkpoint", path);
    return false;
  }
  path_ = path;
  *rows = std::move(loaded);
  return true;
}

bool CheckpointStore::Append(std::span<const TrialRow> rows, std::string* why) {
  std::vector<unsigned char> payload;
  EncodeRows(rows, &payload);
  std::vector<unsigned char> record;
  record.reserve(payload.size() + 20);
  Put(kRecordMagic, &record);
  Put<std::uint64_t>(payload.size(), &record);
  record.insert(record.end(), payload.begin(), payload.end());
  Put(Fnv1a64(payload), &record);
  if (fd_ < 0 || !WriteAll(fd_, record.data(), record.size()) || ::fdatasync(fd_) != 0) {
    *why = SystemError("cannot append to checkpoint", path_);
    return false;
  }
  return true;
}

}  // namespace allanlab::experiments
