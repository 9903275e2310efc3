#pragma once
// Preset YAML specs compiled into the binary (generated from sim/presets/*.yaml at build time).
#include <string_view>
#include <vector>

namespace allanlab::sim {

struct EmbeddedPreset {
  std::string_view name;  // file name without extension
  std::string_view yaml;  // file content
};

const std::vector<EmbeddedPreset>& EmbeddedPresets();

}  // namespace allanlab::sim
