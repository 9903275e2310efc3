#include "tests/support/png_pixels.h"

#include <zlib.h>

#include <algorithm>
#include <cstdlib>
#include <unordered_map>
#include <unordered_set>

#include "tests/support/read_file.h"

namespace allanlab::testing_support {
namespace {

std::uint32_t BigEndian32(const std::string& s, std::size_t at) {
  return (static_cast<std::uint32_t>(static_cast<unsigned char>(s[at])) << 24) |
         (static_cast<std::uint32_t>(static_cast<unsigned char>(s[at + 1])) << 16) |
         (static_cast<std::uint32_t>(static_cast<unsigned char>(s[at + 2])) << 8) |
         static_cast<std::uint32_t>(static_cast<unsigned char>(s[at + 3]));
}

// PNG's Paeth predictor.
int Paeth(int a, int b, int c) {
  const int p = a + b - c;
  const int pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
  if (pa <= pb && pa <= pc) return a;
  return pb <= pc ? b : c;
}

}  // namespace

bool ReadPngPixels(const std::filesystem::path& path, PngPixels* image, std::string* why) {
  const std::string file = ReadAll(path);
  if (file.size() < 33 || file.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0) {
    *why = "not a PNG file";
    return false;
  }
  int width = 0, height = 0, channels = 0;
  std::string deflated;
  for (std::size_t at = 8; at + 12 <= file.size();) {
    const std::uint32_t length = BigEndian32(file, at);
    const std::string type = file.substr(at + 4, 4);
    if (at + 12 + length > file.size()) {
      *why = "truncated chunk " + type;
      return false;
    }
    const std::size_t data = at + 8;
    if (type == "IHDR") {
      width = static_cast<int>(BigEndian32(file, data));
      height = static_cast<int>(BigEndian32(file, data + 4));
      const int depth = static_cast<unsigned char>(file[data + 8]);
      const int colour = static_cast<unsigned char>(file[data + 9]);
      const int interlace = static_cast<unsigned char>(file[data + 12]);
      channels = colour == 0 ? 1 : colour == 4 ? 2 : colour == 2 ? 3 : colour == 6 ? 4 : 0;
      if (depth != 8 || channels == 0 || interlace != 0 || width <= 0 || height <= 0) {
        *why = "unsupported PNG (depth " + std::to_string(depth) + ", colour type " + std::to_string(colour) +
               ", interlace " + std::to_string(interlace) + ")";
        return false;
      }
    } else if (type == "IDAT") {
      deflated += file.substr(data, length);
    } else if (type == "IEND") {
      break;
    }
    at += 12 + length;
  }
  if (channels == 0) {
    *why = "no IHDR chunk";
    return false;
  }
  const std::size_t stride = static_cast<std::size_t>(width) * static_cast<std::size_t>(channels);
  std::vector<unsigned char> raw((stride + 1) * static_cast<std::size_t>(height));
  uLongf raw_size = static_cast<uLongf>(raw.size());
  if (uncompress(raw.data(), &raw_size, reinterpret_cast<const Bytef*>(deflated.data()),
                 static_cast<uLong>(deflated.size())) != Z_OK ||
      raw_size != raw.size()) {
    *why = "the image data does not inflate to " + std::to_string(width) + " x " + std::to_string(height) + " pixels";
    return false;
  }
  // Undo each row's filter (PNG specification, section 9).
  std::vector<unsigned char> pixels(stride * static_cast<std::size_t>(height));
  for (int y = 0; y < height; ++y) {
    const unsigned char filter = raw[static_cast<std::size_t>(y) * (stride + 1)];
    const unsigned char* in = &raw[static_cast<std::size_t>(y) * (stride + 1) + 1];
    unsigned char* row = &pixels[static_cast<std::size_t>(y) * stride];
    const unsigned char* up = y > 0 ? row - stride : nullptr;
    for (std::size_t i = 0; i < stride; ++i) {
      const int a = i >= static_cast<std::size_t>(channels) ? row[i - channels] : 0;
      const int b = up != nullptr ? up[i] : 0;
      const int c = up != nullptr && i >= static_cast<std::size_t>(channels) ? up[i - channels] : 0;
      int predicted = 0;
      switch (filter) {
        case 0: predicted = 0; break;
        case 1: predicted = a; break;
        case 2: predicted = b; break;
        case 3: predicted = (a + b) / 2; break;
        case 4: predicted = Paeth(a, b, c); break;
        default:
          *why = "unknown row filter " + std::to_string(filter);
          return false;
      }
      row[i] = static_cast<unsigned char>(in[i] + predicted);
    }
  }
  image->width = width;
  image->height = height;
  image->rgb.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  for (std::size_t p = 0; p < image->rgb.size(); ++p) {
    const unsigned char* px = &pixels[p * static_cast<std::size_t>(channels)];
    const std::uint32_t r = px[0], g = channels >= 3 ? px[1] : px[0], b = channels >= 3 ? px[2] : px[0];
    image->rgb[p] = (r << 16) | (g << 8) | b;
  }
  return true;
}

double ShareOffBackground(const PngPixels& image) {
  if (image.rgb.empty()) return 0.0;
  std::unordered_map<std::uint32_t, std::size_t> counts;
  for (std::uint32_t c : image.rgb) ++counts[c];
  std::size_t background = 0;
  for (const auto& [colour, n] : counts) background = std::max(background, n);
  return static_cast<double>(image.rgb.size() - background) / static_cast<double>(image.rgb.size());
}

std::size_t DistinctColours(const PngPixels& image) {
  return std::unordered_set<std::uint32_t>(image.rgb.begin(), image.rgb.end()).size();
}

}  // namespace allanlab::testing_support
