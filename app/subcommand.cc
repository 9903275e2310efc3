#include "app/subcommand.h"

#include <iostream>

namespace allanlab::app {

void PrintError(const std::string& command, const std::string& message) {
  // Scripts grep for this prefix and read one line: keep the message on that line.
  std::string line = message;
  for (char& c : line) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  std::cerr << "allanlab" << (command.empty() ? "" : " " + command) << ": error: " << line
            << std::endl;
}

}  // namespace allanlab::app
