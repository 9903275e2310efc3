#include "app/commands/subcommand.h"

#include <new>

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

int RunCommand(const std::string& command, const std::string& out_of_memory_hint,
               const std::function<std::optional<CommandFailure>()>& body) {
  std::optional<CommandFailure> failure;
  try {
    failure = body();
  } catch (const std::bad_alloc&) {
    failure = RuntimeFailure("out of memory" + out_of_memory_hint);
  } catch (const std::exception& e) {
    failure = RuntimeFailure(std::string("internal error: ") + e.what());
  }
  if (!failure) return kExitOk;
  PrintError(command, failure->message);
  return failure->code;
}

}  // namespace allanlab::app
