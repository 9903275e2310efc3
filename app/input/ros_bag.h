#pragma once
// A ROS bag as a record: the sensor_msgs/Imu messages of one topic become a text record with the
// columns time_s (the header stamp, in seconds from the first message's), angular_velocity.x/y/z
// (rad/s) and linear_acceleration.x/y/z (m/s^2), which the text reader reads as any CSV (so
// --column, --columns and --imu pick axes, the time steps are checked and reported as for CSV,
// and the column names state the units, app/input/stated_units.h).
//
// Formats, recognised by their first bytes: ROS 2 MCAP (app/input/mcap_bag.h), ROS 2 sqlite3 .db3
// (app/input/ros2_sqlite_bag.h), ROS 1 .bag (app/input/ros1_bag.h); a ROS 2 bag directory (metadata.yaml
// beside its .mcap or .db3 files) reads its files in name order. The topic: `topic`, or the
// bag's only Imu topic when empty; a missing topic, several Imu topics without one named, or a
// topic with no messages fail with one line listing the bag's topics.
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "app/input/byte_source.h"

namespace allanlab::app {

enum class BagFormat { kMcap, kRos2Sqlite, kRos1 };
std::string_view BagFormatName(BagFormat format);  // "MCAP", "ROS 2 sqlite3", "ROS 1"

// The bag format of `path` (a file, or a ROS 2 bag directory), or nullopt when it is none.
std::optional<BagFormat> DetectBag(const std::string& path);

struct BagRecord {
  std::unique_ptr<ByteSource> text;  // the CSV described above
  std::string description;           // "MCAP bag, topic /imu (sensor_msgs/msg/Imu, 1000 messages)"
  std::string topic;                 // the topic read
};

// kExitOk, or with why (one line, without the path): kExitUsageError when the topic asked is not
// there or not an Imu topic, or none is asked among several; kExitRuntimeError when the bag is
// damaged or truncated, or the topic has no messages.
int OpenBagRecord(const std::string& path, BagFormat format, const std::string& topic, BagRecord* record,
                  std::string* why);

}  // namespace allanlab::app
