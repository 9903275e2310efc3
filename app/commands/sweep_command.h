#pragma once
// `allanlab sweep SPEC.yaml`: runs a Monte Carlo sweep (experiments/sweep_spec.h) through the
// experiment its `driver:` names, aggregates the rows and writes the experiment's report
// (<out>/<name>.csv, .md, plots) with provenance. Trials are checkpointed per batch to
// <out>/<name>.checkpoint (or --checkpoint); after a kill, the same command with --resume
// computes only the missing trials and ends with the same tables. The checkpoint is removed once
// the report is written. Under mpirun the trials are split over the ranks and rank 0 reports.
// Exit codes as app/commands/subcommand.h: 2 bad spec or options, 1 a run or write failure.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>

#include "app/commands/subcommand.h"

namespace allanlab::app {

struct SweepCommandOptions {
  std::string spec_path;
  std::string out_dir = "results/sweeps";
  int threads = 0;  // 0: OpenMP default
  std::string checkpoint_path;  // empty: <out>/<name>.checkpoint
  bool resume = false;
  bool progress = false;
  std::int64_t batch_trials = 64;
};

Subcommand AddSweepCommand(CLI::App* parent);
int RunSweepCommand(const SweepCommandOptions& options, const std::string& command_line);

}  // namespace allanlab::app
