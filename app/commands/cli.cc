#include "app/commands/cli.h"

#include <CLI/CLI.hpp>
#include <iostream>
#include <vector>

#include "app/commands/avar_command.h"
#include "app/commands/diagnose_command.h"
#include "app/commands/diagnosis_benchmark_command.h"
#include "app/commands/fit_command.h"
#include "app/reports/provenance.h"
#include "app/commands/simulate_command.h"
#include "app/commands/subcommand.h"
#include "app/commands/sweep_command.h"
#include "app/commands/validate_command.h"

namespace allanlab::app {
namespace {

// The registry: one entry per subcommand, in the order --help lists them.
using SubcommandFactory = Subcommand (*)(CLI::App* parent);
constexpr SubcommandFactory kSubcommands[] = {
    AddSimulateCommand,
    AddAvarCommand,
    AddFitCommand,
    AddDiagnoseCommand,
    AddDiagnosisBenchmarkCommand,
    AddSweepCommand,
    AddValidateCommand,
};

}  // namespace

int RunCli(int argc, char** argv) {
  CLI::App app{"allanlab: gyro noise simulation and Allan-variance validation", "allanlab"};
  app.require_subcommand(1);
  app.set_version_flag("--version", VersionLine(), "print the version and the git commit, then exit");
  std::vector<Subcommand> subcommands;
  for (SubcommandFactory add : kSubcommands) subcommands.push_back(add(&app));

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // The error belongs to the subcommand the parser had entered, if any.
    std::string command;
    std::string known;
    for (const Subcommand& s : subcommands) {
      if (s.parser->parsed()) command = s.parser->get_name();
      known += (known.empty() ? "" : ", ") + s.parser->get_name();
    }
    // CLI11 reports a mistyped subcommand as a missing one; name it instead.
    if (command.empty() && argc > 1 && argv[1][0] != '-') {
      PrintError("", "unknown command '" + std::string(argv[1]) + "' (known: " + known +
                         "; see allanlab --help)");
      return kExitUsageError;
    }
    const std::string help =
        command.empty() ? "allanlab --help" : "allanlab " + command + " --help";
    PrintError(command, std::string(e.what()) + " (see " + help + ")");
    return kExitUsageError;
  }
  const std::string command_line = QuotedCommandLine(argc, argv);
  for (const Subcommand& s : subcommands) {
    if (s.parser->parsed()) return s.run(command_line);
  }
  return kExitUsageError;  // unreachable: require_subcommand(1)
}

}  // namespace allanlab::app
