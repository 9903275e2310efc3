#include "app/input/imu_message.h"

#include <bit>
#include <cstring>

namespace allanlab::app {
namespace {

// Reads fixed-size fields in order, aligning each to its size relative to `origin` (CDR) or not
// at all (ROS 1), in the byte order of the data.
class FieldReader {
 public:
  FieldReader(std::span<const std::uint8_t> data, std::size_t start, bool little, bool align)
      : data_(data), pos_(start), origin_(start), little_(little), align_(align) {}

  template <typename T>
  bool Read(T* value) {
    if (align_) pos_ = origin_ + (pos_ - origin_ + sizeof(T) - 1) / sizeof(T) * sizeof(T);
    if (pos_ + sizeof(T) > data_.size()) return false;
    std::uint8_t bytes[sizeof(T)];
    std::memcpy(bytes, data_.data() + pos_, sizeof(T));
    if (little_ != (std::endian::native == std::endian::little)) {
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
    }
    std::memcpy(value, bytes, sizeof(T));
    pos_ += sizeof(T);
    return true;
  }
  bool Skip(std::size_t bytes) {
    if (pos_ + bytes > data_.size()) return false;
    pos_ += bytes;
    return true;
  }
  // orientation (4), its covariance (9), angular velocity (3), its covariance (9), linear
  // acceleration (3), its covariance (9): float64 each.
  bool ReadVectors(ImuMessage* m) {
    double skipped = 0.0;
    for (int i = 0; i < 4 + 9; ++i) {
      if (!Read(&skipped)) return false;
    }
    for (double& v : m->angular_velocity) {
      if (!Read(&v)) return false;
    }
    for (int i = 0; i < 9; ++i) {
      if (!Read(&skipped)) return false;
    }
    for (double& v : m->linear_acceleration) {
      if (!Read(&v)) return false;
    }
    return Skip(9 * sizeof(double));
  }

 private:
  std::span<const std::uint8_t> data_;
  std::size_t pos_, origin_;
  bool little_, align_;
};

bool Short(std::size_t size, std::string* why) {
  *why = std::to_string(size) + " bytes end before the message does (not a sensor_msgs/Imu)";
  return false;
}

}  // namespace

bool IsImuType(const std::string& type) { return type == "sensor_msgs/msg/Imu" || type == "sensor_msgs/Imu"; }

bool DecodeImuCdr(std::span<const std::uint8_t> data, ImuMessage* m, std::string* why) {
  if (data.size() < 4) return Short(data.size(), why);
  // Encapsulation: 0x0000 CDR big-endian, 0x0001 CDR little-endian.
  if (data[0] != 0 || data[1] > 1) {
    *why = "CDR encapsulation " + std::to_string(data[0]) + "," + std::to_string(data[1]) +
           " is not plain CDR (big- or little-endian)";
    return false;
  }
  FieldReader r(data, 4, data[1] == 1, true);
  std::int32_t sec = 0;
  std::uint32_t nanosec = 0, frame_id_bytes = 0;
  if (!r.Read(&sec) || !r.Read(&nanosec) || !r.Read(&frame_id_bytes) || !r.Skip(frame_id_bytes) ||
      !r.ReadVectors(m)) {
    return Short(data.size(), why);
  }
  m->stamp_ns = std::int64_t{sec} * 1000000000 + nanosec;
  return true;
}

bool DecodeImuRos1(std::span<const std::uint8_t> data, ImuMessage* m, std::string* why) {
  FieldReader r(data, 0, true, false);
  std::uint32_t seq = 0, sec = 0, nsec = 0, frame_id_bytes = 0;
  if (!r.Read(&seq) || !r.Read(&sec) || !r.Read(&nsec) || !r.Read(&frame_id_bytes) || !r.Skip(frame_id_bytes) ||
      !r.ReadVectors(m)) {
    return Short(data.size(), why);
  }
  m->stamp_ns = std::int64_t{sec} * 1000000000 + nsec;
  return true;
}

}  // namespace allanlab::app
