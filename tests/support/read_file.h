#pragma once
// Whole-file reads for tests that check what a command wrote.
#include <filesystem>
#include <string>

namespace allanlab::testing_support {

// The file's bytes ("" when it cannot be opened: the caller's expectation then fails).
std::string ReadAll(const std::filesystem::path& path);

}  // namespace allanlab::testing_support
