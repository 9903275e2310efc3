#pragma once
// `allanlab validate [--quick]`: the regression check. Reruns the fixed sweep specs of
// experiments/specs/validate/ (quick/ only with --quick; quick/ and full/ otherwise) and compares
// every aggregated number (per point and column: the mean over trials) with the committed golden
// tables in tests/data/validate_quick/<name>.csv. A number has moved when its difference from
// the golden mean exceeds z = 5 standard errors of a difference of two independent means,
// 5 sqrt(se_now^2 + se_golden^2) (plus 1e-12 relative, for per-point constants); a trial count
// that changed or a column that appeared or vanished counts as moved too. Prints each move and
// exits 1 when anything moved. --update rewrites the golden tables instead (after a change whose
// effect is intended; the diff of the tables goes into the commit).
#include <CLI/CLI.hpp>
#include <string>

#include "app/commands/subcommand.h"
#include "experiments/injected_fault.h"

namespace allanlab::app {

struct ValidateCommandOptions {
  bool quick = false;
  bool update = false;
  std::string specs_dir;   // default: <source>/experiments/specs/validate
  std::string golden_dir;  // default: <source>/tests/data/validate_quick
  int threads = 0;
  double z = 5.0;
  // Not on the command line: a test of the check itself runs it with a deliberate error in the
  // drivers (experiments/injected_fault.h) and expects exit 1.
  experiments::InjectedFault fault;
};

Subcommand AddValidateCommand(CLI::App* parent);
int RunValidateCommand(const ValidateCommandOptions& options, const std::string& command_line);

}  // namespace allanlab::app
