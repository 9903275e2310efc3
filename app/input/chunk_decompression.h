#pragma once
// The compressions of ROS bag chunks: zstd and lz4 (frame format) in MCAP, bz2 and lz4 in ROS 1.
// The chunk states its uncompressed size; data that does not decompress to exactly that many
// bytes fails (why: one line naming the compression).
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace allanlab::app {

// compression: "zstd", "lz4" or "bz2"; *out is sized to the stated uncompressed size.
bool DecompressChunk(const std::string& compression, std::span<const std::uint8_t> in, std::vector<std::uint8_t>* out,
                     std::string* why);

}  // namespace allanlab::app
