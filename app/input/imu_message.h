#pragma once
// One sensor_msgs/Imu message, decoded from its two wire encodings: ROS 2's CDR (XCDR1 with its
// 4-byte encapsulation header, little- or big-endian, fields aligned to their size from the end
// of that header) and ROS 1's serialization (little-endian, packed). The fields read: the header
// stamp and the angular velocity and linear acceleration vectors (REP 103: rad/s and m/s^2); the
// orientation and the three covariance arrays are skipped.
#include <cstdint>
#include <span>
#include <string>

namespace allanlab::app {

struct ImuMessage {
  std::int64_t stamp_ns = 0;  // header.stamp, ns since the epoch of the recording clock
  double angular_velocity[3] = {0.0, 0.0, 0.0};     // rad/s
  double linear_acceleration[3] = {0.0, 0.0, 0.0};  // m/s^2
};

// The ROS type names of the message: "sensor_msgs/msg/Imu" (ROS 2) and "sensor_msgs/Imu" (ROS 1).
bool IsImuType(const std::string& type);

// Fail with why = what is wrong ("12 bytes, a sensor_msgs/Imu needs at least 312", ...).
bool DecodeImuCdr(std::span<const std::uint8_t> data, ImuMessage* message, std::string* why);
bool DecodeImuRos1(std::span<const std::uint8_t> data, ImuMessage* message, std::string* why);

}  // namespace allanlab::app
