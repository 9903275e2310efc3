#pragma once
// Reads a ROS 2 bag in its sqlite3 storage (.db3, the default before ROS 2 Iron): the topics
// table (id, name, type, serialization_format) and the messages of Imu topics (topic_id,
// timestamp, data: CDR) in timestamp order, as rosbag2 replays them. A file that is not sqlite,
// lacks those tables, or is damaged fails with one line (why) saying which.
#include <string>

#include "app/input/bag_contents.h"

namespace allanlab::app {

// `topic` empty: every Imu topic's messages; else that topic's only.
bool ReadRos2SqliteBag(const std::string& path, const std::string& topic, BagContents* contents, std::string* why);

}  // namespace allanlab::app
