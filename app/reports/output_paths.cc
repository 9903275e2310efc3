#include "app/reports/output_paths.h"

#include <filesystem>

namespace allanlab::app {

bool CheckDistinctOutputs(const std::vector<std::pair<std::string, std::string>>& outputs,
                          std::string* why) {
  std::vector<std::pair<std::string, std::filesystem::path>> seen;
  for (const auto& [option, path] : outputs) {
    // Absolute first: weakly_canonical leaves a relative path to a missing file relative, and
    // then "x.csv" and "./x.csv" would look different.
    std::error_code ec;
    const std::filesystem::path absolute = std::filesystem::absolute(path, ec).lexically_normal();
    std::filesystem::path canonical = std::filesystem::weakly_canonical(absolute, ec);
    if (ec) canonical = absolute;
    for (const auto& [other_option, other] : seen) {
      if (other == canonical) {
        if (why) *why = other_option + " and " + option + " both name " + path;
        return false;
      }
    }
    seen.emplace_back(option, canonical);
  }
  return true;
}

}  // namespace allanlab::app
