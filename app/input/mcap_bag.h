#pragma once
// Reads a ROS 2 bag in MCAP (the default storage since ROS 2 Iron, https://mcap.dev/spec): the
// records from the leading magic to the footer, Schema/Channel/Message records at the top level
// or inside Chunk records (uncompressed, zstd or lz4 frame); messages of Imu channels decoded as
// CDR (message encoding "cdr") or ROS 1 ("ros1"). A file that ends before its footer and trailing
// magic, a record longer than the file, a chunk that does not decompress to its stated size, or
// whose records do not match their CRC-32 fails with one line (why) saying which.
#include <string>

#include "app/input/bag_contents.h"

namespace allanlab::app {

// `topic` empty: every Imu topic's messages; else that topic's only.
bool ReadMcapBag(const std::string& path, const std::string& topic, BagContents* contents, std::string* why);

}  // namespace allanlab::app
