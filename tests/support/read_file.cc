#include "tests/support/read_file.h"

#include <fstream>
#include <sstream>

namespace allanlab::testing_support {

std::string ReadAll(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

}  // namespace allanlab::testing_support
