#pragma once
// The pixels of a PNG image, for tests that check what a picture shows rather than its file size:
// 8-bit greyscale, grey + alpha, RGB or RGBA, not interlaced (what gnuplot's pngcairo and a headless
// browser's screenshot write).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace allanlab::testing_support {

struct PngPixels {
  int width = 0, height = 0;
  std::vector<std::uint32_t> rgb;  // 0xRRGGBB per pixel, row by row (alpha dropped)
};

// False with *why for a file that is not such a PNG.
bool ReadPngPixels(const std::filesystem::path& path, PngPixels* image, std::string* why);

// The share of pixels that differ from the most common colour (the background), in [0, 1].
double ShareOffBackground(const PngPixels& image);

// The number of distinct colours.
std::size_t DistinctColours(const PngPixels& image);

}  // namespace allanlab::testing_support
