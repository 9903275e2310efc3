// The `allanlab` command: one binary, one subcommand per job.
#include "app/cli.h"

int main(int argc, char** argv) { return allanlab::app::RunCli(argc, argv); }
