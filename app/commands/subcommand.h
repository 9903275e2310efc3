#pragma once
// One `allanlab` subcommand as the CLI registry (app/commands/cli.cc) sees it: its CLI11 parser, owned by
// the top-level app, and what to run once the command line has been parsed into it.
#include <functional>
#include <optional>
#include <string>
#include <utility>

#include <CLI/CLI.hpp>

#include "app/failure.h"

namespace allanlab::app {

struct Subcommand {
  CLI::App* parser = nullptr;
  // Runs the command with the parsed options; `command_line` is the shell-quoted argv for
  // provenance. Returns the exit code; errors have been printed as one line on stderr.
  std::function<int(const std::string& command_line)> run;
};

// Prints "allanlab <command>: error: <message>" as a single line on stderr.
void PrintError(const std::string& command, const std::string& message);

// Runs `body`, turning exceptions into failures (out of memory: `out_of_memory_hint`), prints a
// failure as one error line under `command`, and returns the exit code. Unwinding runs the
// AtomicFile destructors, which remove the temporaries.
int RunCommand(const std::string& command, const std::string& out_of_memory_hint,
               const std::function<std::optional<CommandFailure>()>& body);

}  // namespace allanlab::app
