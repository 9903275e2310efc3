#include "app/cli.h"

#include <CLI/CLI.hpp>

namespace allanlab::app {
int RunCli(int argc, char** argv) {
  CLI::App app{"allanlab: gyro noise simulation and Allan-variance validation"};
  app.require_subcommand(1);
  CLI11_PARSE(app, argc, argv);
  return 0;
}
}  // namespace allanlab::app
