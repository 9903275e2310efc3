#include "app/input/raw_sidecar.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

namespace allanlab::app {
namespace {

std::optional<std::string> SidecarPath(const std::string& record_path) {
  std::vector<std::string> candidates = {record_path + ".json"};
  for (const char* suffix : {".gz", ".xz"}) {
    const std::string s = suffix;
    if (record_path.size() > s.size() && record_path.ends_with(s)) {
      candidates.push_back(record_path.substr(0, record_path.size() - s.size()) + ".json");
    }
  }
  for (const std::string& c : candidates) {
    std::error_code ec;
    if (std::filesystem::is_regular_file(c, ec)) return c;
  }
  return std::nullopt;
}

}  // namespace

bool ReadRawSidecar(const std::string& record_path, std::optional<RawSidecar>* sidecar,
                    std::string* why) {
  sidecar->reset();
  const std::optional<std::string> path = SidecarPath(record_path);
  if (!path) return true;
  std::ifstream in(*path);
  std::stringstream text;
  text << in.rdbuf();
  if (!in) {
    *why = "cannot read the sidecar " + *path;
    return false;
  }
  const nlohmann::json j = nlohmann::json::parse(text.str(), nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object()) {
    *why = "the sidecar " + *path + " is not a JSON object";
    return false;
  }
  // simulate writes the description under "data"; a hand-written sidecar may keep it at the top.
  const nlohmann::json& d = j.contains("data") && j["data"].is_object() ? j["data"] : j;
  RawSidecar s;
  s.path = *path;
  const auto bad = [&](const std::string& key, const std::string& expected) {
    *why = "the sidecar " + *path + ": \"" + key + "\" must be " + expected + ", got " +
           d[key].dump();
    return false;
  };
  if (d.contains("dtype")) {
    if (!d["dtype"].is_string()) return bad("dtype", "a string such as \"<f8\"");
    s.dtype = d["dtype"].get<std::string>();
  }
  if (d.contains("num_samples")) {
    if (!d["num_samples"].is_number_integer() || d["num_samples"].get<std::int64_t>() < 0) {
      return bad("num_samples", "an integer >= 0");
    }
    s.num_samples = d["num_samples"].get<std::int64_t>();
  }
  if (d.contains("sample_rate_hz")) {
    if (!d["sample_rate_hz"].is_number() || !std::isfinite(d["sample_rate_hz"].get<double>()) ||
        !(d["sample_rate_hz"].get<double>() > 0.0)) {
      return bad("sample_rate_hz", "a finite number > 0");
    }
    s.sample_rate_hz = d["sample_rate_hz"].get<double>();
  }
  if (d.contains("units")) {
    if (!d["units"].is_string()) return bad("units", "a string such as \"rad/s\"");
    s.units = d["units"].get<std::string>();
  }
  *sidecar = std::move(s);
  return true;
}

}  // namespace allanlab::app
