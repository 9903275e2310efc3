#pragma once
// How every part of the command line reports failure: the process exit codes and a failed run
// (its code and the one line to print). Shared by app/commands/, app/input/ and app/reports/.
#include <string>
#include <utility>

namespace allanlab::app {

inline constexpr int kExitOk = 0;
inline constexpr int kExitRuntimeError = 1;  // the inputs were fine, the work failed (I/O, ...)
inline constexpr int kExitUsageError = 2;    // the command line or an input value is wrong

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

}  // namespace allanlab::app
