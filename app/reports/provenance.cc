#include "app/reports/provenance.h"

#include <charconv>
#include <cstdlib>
#include <ctime>
#include <system_error>

#include "allanlab_git_sha.h"  // generated at build time by cmake/GitSha.cmake

#ifndef ALLANLAB_VERSION
#define ALLANLAB_VERSION "unknown"
#endif
#ifndef ALLANLAB_BUILD_TYPE
#define ALLANLAB_BUILD_TYPE "unknown"
#endif

namespace allanlab::app {
namespace {

std::string UtcDate() {
  std::time_t now = std::time(nullptr);
  if (const char* epoch = std::getenv("SOURCE_DATE_EPOCH"); epoch && *epoch) {
    char* end = nullptr;
    const long long pinned = std::strtoll(epoch, &end, 10);
    if (*end == '\0') now = static_cast<std::time_t>(pinned);
  }
  std::tm tm{};
  gmtime_r(&now, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

std::string OneLine(std::string text) {
  for (char& c : text) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return text;
}

bool NeedsQuoting(std::string_view arg) {
  if (arg.empty()) return true;
  for (char c : arg) {
    const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                       std::string_view("-_./=:,+@%^").find(c) != std::string_view::npos;
    if (!plain) return true;
  }
  return false;
}

}  // namespace

std::string VersionLine() {
  return std::string("allanlab ") + ALLANLAB_VERSION + " (git " + ALLANLAB_GIT_SHA + ", " +
         ALLANLAB_BUILD_TYPE + ")";
}

Provenance MakeProvenance(std::string command, std::string command_line) {
  Provenance p;
  p.command = std::move(command);
  p.version = ALLANLAB_VERSION;
  p.git_sha = ALLANLAB_GIT_SHA;
  p.build_type = ALLANLAB_BUILD_TYPE;
  p.utc_date = UtcDate();
  p.command_line = std::move(command_line);
  return p;
}

std::string QuotedCommandLine(int argc, const char* const* argv) {
  std::string line;
  for (int i = 0; i < argc; ++i) {
    if (i > 0) line += ' ';
    const std::string_view arg = argv[i];
    if (!NeedsQuoting(arg)) {
      line += arg;
      continue;
    }
    line += '\'';
    for (char c : arg) {
      if (c == '\'') {
        line += "'\\''";
      } else {
        line += c;
      }
    }
    line += '\'';
  }
  return line;
}

std::string ProvenanceCommentLines(const Provenance& p) {
  std::string out = "# allanlab " + p.command + " " + p.version + " (git " + p.git_sha + ", " +
                    p.build_type + ")\n";
  out += "# date: " + p.utc_date + "\n";
  out += "# command: " + OneLine(p.command_line) + "\n";
  for (const auto& [key, value] : p.fields) out += "# " + key + ": " + OneLine(value) + "\n";
  return out;
}

nlohmann::ordered_json ProvenanceJson(const Provenance& p) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  j["command"] = p.command;
  j["version"] = p.version;
  j["git_sha"] = p.git_sha;
  j["build_type"] = p.build_type;
  j["utc_date"] = p.utc_date;
  j["command_line"] = p.command_line;
  for (const auto& [key, value] : p.fields) j[key] = value;
  return j;
}

}  // namespace allanlab::app
