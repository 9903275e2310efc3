#pragma once
// Reads a ROS 1 bag (format 2.0, http://wiki.ros.org/Bags/Format/2.0): its records in file
// order, connection and message records at the top level or inside chunks (uncompressed, bz2 or
// lz4), messages of sensor_msgs/Imu connections decoded from the ROS 1 serialization. A record
// that runs past the end of the file or a chunk that does not decompress to its stated size fails
// with one line (why) saying which.
#include <string>

#include "app/input/bag_contents.h"

namespace allanlab::app {

// `topic` empty: every Imu topic's messages; else that topic's only.
bool ReadRos1Bag(const std::string& path, const std::string& topic, BagContents* contents, std::string* why);

}  // namespace allanlab::app
