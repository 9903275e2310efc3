#pragma once
// What the ROS bag readers (app/input/mcap_bag.h, app/input/ros2_sqlite_bag.h, app/input/ros1_bag.h) return: every
// topic with its type, and the sensor_msgs/Imu messages of the Imu topics in file order. Choosing
// the topic and turning its messages into a record is app/input/ros_bag.h's.
#include <map>
#include <string>
#include <vector>

#include "app/input/imu_message.h"

namespace allanlab::app {

struct BagContents {
  std::map<std::string, std::string> topics;  // topic -> ROS type name
  // Imu topic -> its messages; only `topic` when the reader was given one.
  std::map<std::string, std::vector<ImuMessage>> imu;
};

}  // namespace allanlab::app
