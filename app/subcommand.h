#pragma once
// One `allanlab` subcommand as the CLI registry (app/cli.cc) sees it: its CLI11 parser, owned by
// the top-level app, and what to run once the command line has been parsed into it.
#include <functional>
#include <optional>
#include <string>
#include <utility>

#include <CLI/CLI.hpp>

namespace allanlab::app {

// Process exit codes shared by all subcommands.
inline constexpr int kExitOk = 0;
inline constexpr int kExitRuntimeError = 1;  // the inputs were fine, the work failed (I/O, ...)
inline constexpr int kExitUsageError = 2;    // the command line or an input value is wrong

struct Subcommand {
  CLI::App* parser = nullptr;
  // Runs the command with the parsed options; `command_line` is the shell-quoted argv for
  // provenance. Returns the exit code; errors have been printed as one line on stderr.
  std::function<int(const std::string& command_line)> run;
};

// Prints "allanlab <command>: error: <message>" as a single line on stderr.
void PrintError(const std::string& command, const std::string& message);

// A failed run: the exit code and the one line to print.
struct CommandFailure {
  int code = kExitOk;
  std::string message;
};
inline CommandFailure UsageFailure(std::string message) {
  return {kExitUsageError, std::move(message)};
}
inline CommandFailure RuntimeFailure(std::string message) {
  return {kExitRuntimeError, std::move(message)};
}

// Runs `body`, turning exceptions into failures (out of memory: `out_of_memory_hint`), prints a
// failure as one error line under `command`, and returns the exit code. Unwinding runs the
// AtomicFile destructors, which remove the temporaries.
int RunCommand(const std::string& command, const std::string& out_of_memory_hint,
               const std::function<std::optional<CommandFailure>()>& body);

}  // namespace allanlab::app
