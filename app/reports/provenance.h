#pragma once
// Where an output file came from: tool version, git SHA, build type, UTC date, the command line and
// the command's own inputs (preset, seed, ...). Every file allanlab writes carries it, as `#`
// comment lines at the top of a CSV or as an object in a JSON sidecar, so that a result can be
// regenerated from the file alone.
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace allanlab::app {

struct Provenance {
  std::string command;       // subcommand, e.g. "simulate"
  std::string version;       // allanlab version (CMake project version)
  std::string git_sha;       // commit the binary was configured from
  std::string build_type;    // CMake build type
  std::string utc_date;      // ISO 8601, e.g. "2026-11-22T11:47:03Z"
  std::string command_line;  // shell-quoted argv
  // The command's inputs in the order they are printed; values are strings with their unit.
  std::vector<std::pair<std::string, std::string>> fields;

  void Add(std::string key, std::string value) {
    fields.emplace_back(std::move(key), std::move(value));
  }
};

// Fills version, git SHA, build type and the date (now, or SOURCE_DATE_EPOCH when it is set, the
// reproducible-builds convention for pinning timestamps).
Provenance MakeProvenance(std::string command, std::string command_line);

// "allanlab 0.1.0 (git abc123, Release)": what `allanlab --version` prints.
std::string VersionLine();

// argv joined with spaces, each argument shell-quoted when it needs to be, so the line can be
// pasted back into a shell.
std::string QuotedCommandLine(int argc, const char* const* argv);

// "# allanlab simulate 0.1.0 (git abc123, Release)\n# date: ...\n# command: ...\n# key: value\n".
// Newlines inside values become spaces so that each field stays on one comment line.
std::string ProvenanceCommentLines(const Provenance& provenance);

// The same content as a JSON object, in the same order (keys: command, version, git_sha,
// build_type, utc_date, command_line, and every field).
nlohmann::ordered_json ProvenanceJson(const Provenance& provenance);


}  // namespace allanlab::app
