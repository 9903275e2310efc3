#include "app/input/ros_bag.h"

#include <algorithm>
#include <charconv>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <utility>
#include <vector>

#include "app/input/bag_contents.h"
#include "app/input/mcap_bag.h"
#include "app/input/ros1_bag.h"
#include "app/input/ros2_sqlite_bag.h"
#include "app/failure.h"

namespace allanlab::app {
namespace {

namespace fs = std::filesystem;

std::optional<BagFormat> FormatOfFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char head[16] = {};
  if (!in.read(head, sizeof head)) return std::nullopt;
  if (std::memcmp(head, "\x89MCAP0\r\n", 8) == 0) return BagFormat::kMcap;
  if (std::memcmp(head, "SQLite format 3", 16) == 0) return BagFormat::kRos2Sqlite;
  if (std::memcmp(head, "#ROSBAG V2.0\n", 13) == 0) return BagFormat::kRos1;
  return std::nullopt;
}

// The storage files of a ROS 2 bag directory, in name order (rosbag2 numbers them _0, _1, ...).
std::vector<std::string> BagFiles(const std::string& path) {
  std::error_code ec;
  if (!fs::is_directory(path, ec)) return {path};
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(path, ec)) {
    if (e.path().extension() == ".mcap" || e.path().extension() == ".db3") files.push_back(e.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// The messages as CSV text, formatted a block of rows at a time.
class ImuText : public ByteSource {
 public:
  explicit ImuText(std::vector<ImuMessage> messages) : messages_(std::move(messages)) {
    pending_ = "time_s,angular_velocity.x,angular_velocity.y,angular_velocity.z,"
               "linear_acceleration.x,linear_acceleration.y,linear_acceleration.z\n";
  }
  bool Read(std::span<char> out, std::size_t* got, std::string*) override {
    while (pending_.size() - offset_ < out.size() && next_ < messages_.size()) Format();
    *got = std::min(out.size(), pending_.size() - offset_);
    std::memcpy(out.data(), pending_.data() + offset_, *got);
    offset_ += *got;
    return true;
  }
  Compression compression() const override { return Compression::kNone; }

 private:
  void Format() {
    pending_.erase(0, offset_);
    offset_ = 0;
    const std::int64_t t0 = messages_.front().stamp_ns;
    char buffer[32];
    for (std::size_t end = std::min(messages_.size(), next_ + 4096); next_ < end; ++next_) {
      const ImuMessage& m = messages_[next_];
      // Nanoseconds from the first stamp, exact in a double up to 104 days.
      Append(static_cast<double>(m.stamp_ns - t0) * 1e-9, buffer);
      for (double v : m.angular_velocity) Append(v, buffer, ',');
      for (double v : m.linear_acceleration) Append(v, buffer, ',');
      pending_ += '\n';
    }
  }
  void Append(double v, char* buffer, char separator = 0) {
    if (separator) pending_ += separator;
    const auto r = std::to_chars(buffer, buffer + 32, v);  // shortest text that reads back exactly
    pending_.append(buffer, r.ptr);
  }

  std::vector<ImuMessage> messages_;
  std::size_t next_ = 0;
  std::string pending_;
  std::size_t offset_ = 0;
};

std::string TopicList(const BagContents& c) {
  std::string list;
  for (const auto& [name, type] : c.topics) list += (list.empty() ? "" : ", ") + name + " (" + type + ")";
  return list.empty() ? "none" : list;
}

}  // namespace

std::string_view BagFormatName(BagFormat format) {
  switch (format) {
    case BagFormat::kMcap: return "MCAP";
    case BagFormat::kRos2Sqlite: return "ROS 2 sqlite3";
    case BagFormat::kRos1: return "ROS 1";
  }
  return "?";
}

std::optional<BagFormat> DetectBag(const std::string& path) {
  const std::vector<std::string> files = BagFiles(path);
  if (files.empty()) return std::nullopt;
  return FormatOfFile(files.front());
}

int OpenBagRecord(const std::string& path, BagFormat format, const std::string& topic, BagRecord* record,
                  std::string* why) {
  BagContents contents;
  for (const std::string& file : BagFiles(path)) {
    const std::optional<BagFormat> f = FormatOfFile(file);
    BagContents part;
    std::string bad;
    const bool ok = f == BagFormat::kMcap         ? ReadMcapBag(file, topic, &part, &bad)
                    : f == BagFormat::kRos2Sqlite ? ReadRos2SqliteBag(file, topic, &part, &bad)
                    : f == BagFormat::kRos1       ? ReadRos1Bag(file, topic, &part, &bad)
                                                  : (bad = "not a ROS bag file", false);
    if (!ok) {
      *why = (file == path ? std::string() : file + ": ") + bad;
      return kExitRuntimeError;
    }
    contents.topics.insert(part.topics.begin(), part.topics.end());
    for (auto& [name, list] : part.imu) {
      std::vector<ImuMessage>& all = contents.imu[name];
      all.insert(all.end(), list.begin(), list.end());
    }
  }
  std::string chosen = topic;
  if (topic.empty()) {
    if (contents.imu.size() != 1) {
      *why = std::string(contents.imu.empty() ? "no sensor_msgs/Imu topic" : "several sensor_msgs/Imu topics") +
             " in the bag (topics: " + TopicList(contents) + ")" + (contents.imu.empty() ? "" : ": name one with --topic");
      return contents.imu.empty() ? kExitRuntimeError : kExitUsageError;
    }
    chosen = contents.imu.begin()->first;
  } else if (!contents.topics.count(topic)) {
    *why = "no topic " + topic + " in the bag (topics: " + TopicList(contents) + ")";
    return kExitUsageError;
  } else if (!contents.imu.count(topic)) {
    *why = "topic " + topic + " holds " + contents.topics[topic] + ", not sensor_msgs/Imu";
    return kExitUsageError;
  }
  std::vector<ImuMessage>& messages = contents.imu[chosen];
  if (messages.empty()) {
    *why = "topic " + chosen + " has no messages";
    return kExitRuntimeError;
  }
  record->description = std::string(BagFormatName(format)) + " bag, topic " + chosen + " (" +
                        contents.topics[chosen] + ", " + std::to_string(messages.size()) + " messages)";
  record->topic = chosen;
  record->text = std::make_unique<ImuText>(std::move(messages));
  return kExitOk;
}

}  // namespace allanlab::app
