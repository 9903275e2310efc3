#include "app/input/mcap_bag.h"

#include "app/input/chunk_decompression.h"

#include <cstdint>
#include <algorithm>
#include <cstring>
#include <fstream>
#include <span>
#include <unordered_map>
#include <vector>

#include <zlib.h>

namespace allanlab::app {
namespace {

constexpr std::uint8_t kMagic[8] = {0x89, 'M', 'C', 'A', 'P', 0x30, '\r', '\n'};
enum Op : std::uint8_t { kHeader = 0x01, kFooter = 0x02, kSchema = 0x03, kChannel = 0x04, kMessage = 0x05,
                         kChunk = 0x06, kDataEnd = 0x0F };

// Little-endian fields of one record's content; any read past its end marks it bad.
class Fields {
 public:
  explicit Fields(std::span<const std::uint8_t> data) : data_(data) {}
  template <typename T>
  T Get() {
    T v{};
    if (pos_ + sizeof(T) > data_.size()) {
      bad_ = true;
      return v;
    }
    std::memcpy(&v, data_.data() + pos_, sizeof(T));  // MCAP is little-endian, as every host we build on
    pos_ += sizeof(T);
    return v;
  }
  std::string String() {
    const auto n = Get<std::uint32_t>();
    if (bad_ || pos_ + n > data_.size()) {
      bad_ = true;
      return {};
    }
    std::string s(reinterpret_cast<const char*>(data_.data() + pos_), n);
    pos_ += n;
    return s;
  }
  std::span<const std::uint8_t> Rest() { return data_.subspan(std::min(pos_, data_.size())); }
  std::span<const std::uint8_t> Bytes(std::uint64_t n) {
    if (pos_ + n > data_.size()) {
      bad_ = true;
      return {};
    }
    auto s = data_.subspan(pos_, n);
    pos_ += n;
    return s;
  }
  bool bad() const { return bad_; }

 private:
  std::span<const std::uint8_t> data_;
  std::size_t pos_ = 0;
  bool bad_ = false;
};

std::uint32_t Crc32(std::span<const std::uint8_t> data) {
  uLong crc = crc32(0L, Z_NULL, 0);
  for (std::size_t pos = 0; pos < data.size();) {
    const auto n = static_cast<uInt>(std::min<std::size_t>(data.size() - pos, 1u << 30));
    crc = crc32(crc, data.data() + pos, n);
    pos += n;
  }
  return static_cast<std::uint32_t>(crc);
}

struct Channel {
  std::string topic, encoding;
  bool imu = false;
};

class McapReader {
 public:
  McapReader(const std::string& topic, BagContents* contents) : topic_(topic), contents_(contents) {}

  // One record (top level or inside a chunk); false with *why on a malformed one.
  bool Record(std::uint8_t op, std::span<const std::uint8_t> content, std::string* why) {
    Fields f(content);
    switch (op) {
      case kSchema: {
        const auto id = f.Get<std::uint16_t>();
        schemas_[id] = f.String();
        break;
      }
      case kChannel: {
        const auto id = f.Get<std::uint16_t>();
        const auto schema = f.Get<std::uint16_t>();
        Channel c;
        c.topic = f.String();
        c.encoding = f.String();
        const auto type = schemas_.find(schema);
        const std::string type_name = type == schemas_.end() ? std::string() : type->second;
        if (!f.bad()) contents_->topics[c.topic] = type_name;
        c.imu = IsImuType(type_name) && (topic_.empty() || topic_ == c.topic);
        if (c.imu) contents_->imu[c.topic];
        channels_[id] = std::move(c);
        break;
      }
      case kMessage: {
        const auto id = f.Get<std::uint16_t>();
        f.Get<std::uint32_t>();  // sequence
        f.Get<std::uint64_t>();  // log time
        f.Get<std::uint64_t>();  // publish time
        if (f.bad()) break;
        const auto c = channels_.find(id);
        if (c == channels_.end() || !c->second.imu) break;
        ImuMessage m;
        std::string bad;
        const bool ros1 = c->second.encoding == "ros1";
        if (!ros1 && c->second.encoding != "cdr") {
          *why = "topic " + c->second.topic + ": message encoding '" + c->second.encoding + "' (expected cdr or ros1)";
          return false;
        }
        if (!(ros1 ? DecodeImuRos1(f.Rest(), &m, &bad) : DecodeImuCdr(f.Rest(), &m, &bad))) {
          std::vector<ImuMessage>& list = contents_->imu[c->second.topic];
          *why = "topic " + c->second.topic + ": message " + std::to_string(list.size() + 1) + ": " + bad;
          return false;
        }
        contents_->imu[c->second.topic].push_back(m);
        break;
      }
      case kChunk:
        return Chunk(f, why);
      default:
        break;
    }
    if (f.bad()) {
      *why = "a record of type " + std::to_string(op) + " is shorter than its fields";
      return false;
    }
    return true;
  }

 private:
  bool Chunk(Fields& f, std::string* why) {
    f.Get<std::uint64_t>();  // message start time
    f.Get<std::uint64_t>();  // message end time
    const auto size = f.Get<std::uint64_t>();
    const auto crc = f.Get<std::uint32_t>();  // of the uncompressed records; 0: not computed
    const std::string compression = f.String();
    const auto stored = f.Get<std::uint64_t>();
    const std::span<const std::uint8_t> records = f.Bytes(stored);
    if (f.bad()) {
      *why = "a chunk record is shorter than its fields";
      return false;
    }
    std::vector<std::uint8_t> plain;
    std::span<const std::uint8_t> data = records;
    if (!compression.empty()) {
      if (size > (std::uint64_t{1} << 34)) {
        *why = "a chunk states " + std::to_string(size) + " uncompressed bytes";
        return false;
      }
      plain.resize(size);
      if (!DecompressChunk(compression, records, &plain, why)) return false;
      data = plain;
    }
    if (crc != 0 && Crc32(data) != crc) {
      *why = "a chunk's records do not match their CRC (a damaged file)";
      return false;
    }
    std::size_t pos = 0;
    while (pos < data.size()) {
      if (data.size() - pos < 9) {
        *why = "a chunk ends inside a record";
        return false;
      }
      const std::uint8_t op = data[pos];
      std::uint64_t length = 0;
      std::memcpy(&length, data.data() + pos + 1, 8);
      if (length > data.size() - pos - 9) {
        *why = "a record in a chunk is longer than the chunk";
        return false;
      }
      if (op == kChunk) {
        *why = "a chunk inside a chunk";
        return false;
      }
      if (!Record(op, data.subspan(pos + 9, length), why)) return false;
      pos += 9 + length;
    }
    return true;
  }

  std::string topic_;
  BagContents* contents_;
  std::unordered_map<std::uint16_t, std::string> schemas_;
  std::unordered_map<std::uint16_t, Channel> channels_;
};

}  // namespace

bool ReadMcapBag(const std::string& path, const std::string& topic, BagContents* contents, std::string* why) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    *why = "cannot open " + path;
    return false;
  }
  std::uint8_t magic[8];
  if (!in.read(reinterpret_cast<char*>(magic), 8) || std::memcmp(magic, kMagic, 8) != 0) {
    *why = "not an MCAP file (no leading magic)";
    return false;
  }
  McapReader reader(topic, contents);
  std::vector<std::uint8_t> content;
  while (true) {
    std::uint8_t head[9];
    if (!in.read(reinterpret_cast<char*>(head), 9)) {
      *why = "truncated MCAP: the file ends before its footer (an interrupted recording?)";
      return false;
    }
    std::uint64_t length = 0;
    std::memcpy(&length, head + 1, 8);
    if (length > (std::uint64_t{1} << 36)) {
      *why = "a record states " + std::to_string(length) + " bytes: not an MCAP record";
      return false;
    }
    content.resize(length);
    if (!in.read(reinterpret_cast<char*>(content.data()), static_cast<std::streamsize>(length))) {
      *why = "truncated MCAP: a record of " + std::to_string(length) + " bytes runs past the end of the file";
      return false;
    }
    if (head[0] == kFooter) break;
    if (!reader.Record(head[0], content, why)) return false;
  }
  if (!in.read(reinterpret_cast<char*>(magic), 8) || std::memcmp(magic, kMagic, 8) != 0) {
    *why = "truncated MCAP: no trailing magic after the footer";
    return false;
  }
  return true;
}

}  // namespace allanlab::app
