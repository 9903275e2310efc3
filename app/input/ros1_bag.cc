#include "app/input/ros1_bag.h"

#include "app/input/chunk_decompression.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <span>
#include <unordered_map>
#include <vector>

namespace allanlab::app {
namespace {

constexpr char kMagic[] = "#ROSBAG V2.0\n";
enum Op : std::uint8_t { kMessageData = 0x02, kChunk = 0x05, kConnection = 0x07 };

// A record header (or a connection header): name=value fields, each after its int32 length.
bool ParseFields(std::span<const std::uint8_t> bytes, std::map<std::string, std::string>* fields) {
  std::size_t pos = 0;
  while (pos < bytes.size()) {
    if (bytes.size() - pos < 4) return false;
    std::uint32_t n = 0;
    std::memcpy(&n, bytes.data() + pos, 4);
    pos += 4;
    if (n > bytes.size() - pos) return false;
    const std::string field(reinterpret_cast<const char*>(bytes.data() + pos), n);
    pos += n;
    const std::size_t eq = field.find('=');
    if (eq == std::string::npos) return false;
    (*fields)[field.substr(0, eq)] = field.substr(eq + 1);
  }
  return true;
}

template <typename T>
bool FieldValue(const std::map<std::string, std::string>& fields, const std::string& name, T* value) {
  const auto it = fields.find(name);
  if (it == fields.end() || it->second.size() != sizeof(T)) return false;
  std::memcpy(value, it->second.data(), sizeof(T));
  return true;
}

struct Connection {
  std::string topic;
  bool imu = false;
};

class Ros1Reader {
 public:
  Ros1Reader(const std::string& topic, BagContents* contents) : topic_(topic), contents_(contents) {}

  // The records in `bytes` (a chunk's, or false when one runs past its end).
  bool Records(std::span<const std::uint8_t> bytes, std::string* why) {
    std::size_t pos = 0;
    while (pos < bytes.size()) {
      std::uint32_t header_len = 0, data_len = 0;
      if (bytes.size() - pos < 4) return Truncated("a chunk", why);
      std::memcpy(&header_len, bytes.data() + pos, 4);
      if (header_len > bytes.size() - pos - 4 || bytes.size() - pos - 4 - header_len < 4) {
        return Truncated("a chunk", why);
      }
      const auto header = bytes.subspan(pos + 4, header_len);
      std::memcpy(&data_len, bytes.data() + pos + 4 + header_len, 4);
      const std::size_t data_at = pos + 8 + header_len;
      if (data_len > bytes.size() - data_at) return Truncated("a chunk", why);
      if (!Record(header, bytes.subspan(data_at, data_len), why)) return false;
      pos = data_at + data_len;
    }
    return true;
  }

  bool Record(std::span<const std::uint8_t> header, std::span<const std::uint8_t> data, std::string* why) {
    std::map<std::string, std::string> fields;
    std::uint8_t op = 0;
    if (!ParseFields(header, &fields) || !FieldValue(fields, "op", &op)) {
      *why = "a record header is malformed (not a ROS 1 bag record)";
      return false;
    }
    if (op == kConnection) {
      std::uint32_t id = 0;
      std::map<std::string, std::string> connection;
      if (!FieldValue(fields, "conn", &id) || !ParseFields(data, &connection)) {
        *why = "a connection record is malformed";
        return false;
      }
      Connection c;
      c.topic = fields.count("topic") ? fields["topic"] : connection["topic"];
      const std::string type = connection["type"];
      contents_->topics[c.topic] = type;
      c.imu = IsImuType(type) && (topic_.empty() || topic_ == c.topic);
      if (c.imu) contents_->imu[c.topic];
      connections_[id] = c;
    } else if (op == kMessageData) {
      std::uint32_t id = 0;
      if (!FieldValue(fields, "conn", &id)) {
        *why = "a message record has no connection";
        return false;
      }
      const auto c = connections_.find(id);
      if (c == connections_.end() || !c->second.imu) return true;
      std::vector<ImuMessage>& list = contents_->imu[c->second.topic];
      ImuMessage m;
      std::string bad;
      if (!DecodeImuRos1(data, &m, &bad)) {
        *why = "topic " + c->second.topic + ": message " + std::to_string(list.size() + 1) + ": " + bad;
        return false;
      }
      list.push_back(m);
    } else if (op == kChunk) {
      std::uint32_t size = 0;
      if (!FieldValue(fields, "size", &size) || !fields.count("compression")) {
        *why = "a chunk record is malformed";
        return false;
      }
      const std::string compression = fields["compression"];
      if (compression == "none") return Records(data, why);
      std::vector<std::uint8_t> plain(size);
      if (!DecompressChunk(compression, data, &plain, why)) return false;
      return Records(plain, why);
    }
    return true;
  }

 private:
  static bool Truncated(const std::string& where, std::string* why) {
    *why = where + " ends inside a record";
    return false;
  }

  std::string topic_;
  BagContents* contents_;
  std::unordered_map<std::uint32_t, Connection> connections_;
};

}  // namespace

bool ReadRos1Bag(const std::string& path, const std::string& topic, BagContents* contents, std::string* why) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    *why = "cannot open " + path;
    return false;
  }
  char magic[sizeof kMagic - 1];
  if (!in.read(magic, sizeof magic) || std::memcmp(magic, kMagic, sizeof magic) != 0) {
    *why = "not a ROS 1 bag (no '#ROSBAG V2.0' line)";
    return false;
  }
  Ros1Reader reader(topic, contents);
  std::vector<std::uint8_t> header, data;
  while (true) {
    std::uint32_t length = 0;
    if (!in.read(reinterpret_cast<char*>(&length), 4)) {
      if (in.gcount() == 0) break;  // the end, between records
      *why = "truncated ROS 1 bag: the file ends inside a record";
      return false;
    }
    header.resize(length);
    std::uint32_t data_length = 0;
    if (!in.read(reinterpret_cast<char*>(header.data()), length) ||
        !in.read(reinterpret_cast<char*>(&data_length), 4)) {
      *why = "truncated ROS 1 bag: the file ends inside a record";
      return false;
    }
    data.resize(data_length);
    if (!in.read(reinterpret_cast<char*>(data.data()), data_length)) {
      *why = "truncated ROS 1 bag: a record of " + std::to_string(data_length) + " bytes runs past the end of the file";
      return false;
    }
    if (!reader.Record(header, data, why)) return false;
  }
  return true;
}

}  // namespace allanlab::app
