#pragma once
// Checks on the set of files one command run will write.
#include <string>
#include <utility>
#include <vector>

namespace allanlab::app {

// Fails when two outputs name the same file (after resolving "./", "..", symlinks and relative
// paths): the second rename would silently win. `outputs` are (option, path) pairs; the message
// is "<option> and <option> both name <path>".
bool CheckDistinctOutputs(const std::vector<std::pair<std::string, std::string>>& outputs,
                          std::string* why);

}  // namespace allanlab::app
