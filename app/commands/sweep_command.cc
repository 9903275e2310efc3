#include "app/commands/sweep_command.h"

#include <omp.h>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include "app/reports/provenance.h"
#include "experiments/aggregate.h"
#include "experiments/mpi_world.h"
#include "experiments/registry.h"
#include "experiments/runner.h"
#include "experiments/sweep_spec.h"

namespace allanlab::app {
namespace {

constexpr const char* kCommand = "sweep";

std::string KnownExperiments() {
  std::string known;
  for (const std::string& name : experiments::ExperimentNames()) {
    if (!known.empty()) known += ", ";
    known += name;
  }
  return known;
}

std::optional<CommandFailure> Sweep(const SweepCommandOptions& options,
                                    const std::string& command_line) {
  if (options.threads < 0) return UsageFailure("--threads must be >= 0 (0: all cores)");
  if (options.batch_trials < 1) return UsageFailure("--batch must be >= 1");
  experiments::SweepSpec spec;
  std::string why;
  if (!experiments::LoadSweepSpecFile(options.spec_path, &spec, &why)) return UsageFailure(why);
  const std::unique_ptr<experiments::Experiment> experiment =
      experiments::MakeExperiment(spec.driver);
  if (!experiment) {
    return UsageFailure("no experiment \"" + spec.driver + "\" (known: " + KnownExperiments() + ")");
  }
  std::error_code ec;
  std::filesystem::create_directories(options.out_dir, ec);
  if (ec) return RuntimeFailure("cannot create " + options.out_dir + ": " + ec.message());

  experiments::RunnerOptions runner;
  runner.threads = options.threads;
  runner.batch_trials = options.batch_trials;
  runner.checkpoint_path = options.checkpoint_path.empty()
                               ? options.out_dir + "/" + spec.name + ".checkpoint"
                               : options.checkpoint_path;
  runner.resume = options.resume;
  runner.progress = options.progress;
  experiments::RunSummary run;
  if (!experiments::RunSweep(spec, experiment->Driver(), runner, &run)) {
    return RuntimeFailure(run.message);
  }
  const experiments::RankInfo ranks = experiments::CurrentRanks();
  if (ranks.rank != 0) {
    std::remove((runner.checkpoint_path + ".rank" + std::to_string(ranks.rank) + "of" +
                 std::to_string(ranks.size)).c_str());
    return std::nullopt;
  }
  const std::vector<experiments::PointStats> stats = experiments::Aggregate(run);
  const Provenance provenance = MakeProvenance(kCommand, command_line);
  experiments::ReportContext context;
  context.output_dir = options.out_dir;
  context.git_sha = provenance.git_sha;
  context.build_type = provenance.build_type;
  context.command_line = provenance.command_line;
  context.date_utc = provenance.utc_date;
  context.threads = options.threads > 0 ? options.threads : omp_get_max_threads();
  context.ranks = ranks.size;
  context.wall_time_s = run.wall_time_s;
  if (!experiment->WriteReport(spec, run, stats, context, &why)) return RuntimeFailure(why);
  std::remove((ranks.size == 1 ? runner.checkpoint_path
                               : runner.checkpoint_path + ".rank0of" + std::to_string(ranks.size))
                  .c_str());
  std::ostringstream out;
  out << "sweep " << spec.name << ": " << spec.points.size() << " points x " << spec.trials
      << " trials (" << run.trials_failed << " failed, " << run.trials_resumed << " resumed) in "
      << run.wall_time_s << " s; report in " << options.out_dir << "/" << spec.name << ".*\n";
  std::cout << out.str() << std::flush;
  return std::nullopt;
}

}  // namespace

Subcommand AddSweepCommand(CLI::App* parent) {
  auto options = std::make_shared<SweepCommandOptions>();
  CLI::App* cmd = parent->add_subcommand(
      kCommand,
      "Run a Monte Carlo sweep spec (YAML) through its experiment and write the report; "
      "checkpointed, resumable, OpenMP across trials, MPI across ranks under mpirun.");
  cmd->add_option("SPEC", options->spec_path, "sweep spec (YAML file)")->required()->type_name("");
  cmd->add_option("--out", options->out_dir, "report directory (default results/sweeps)")
      ->type_name("DIR");
  cmd->add_option("--threads", options->threads, "OpenMP threads (default 0: all cores)")
      ->type_name("N");
  cmd->add_option("--checkpoint", options->checkpoint_path,
                  "checkpoint store (default <out>/<name>.checkpoint; removed after the report)")
      ->type_name("FILE");
  cmd->add_flag("--resume", options->resume,
                "continue an interrupted run from its checkpoint (same spec), computing only the "
                "missing trials");
  cmd->add_flag("--progress", options->progress,
                "progress lines on stderr even when it is not a terminal");
  cmd->add_option("--batch", options->batch_trials, "trials per checkpointed batch (default 64)")
      ->type_name("N");
  cmd->footer("Exit status: 0 ok, 1 run or write failure, 2 bad spec or options.");
  return {cmd, [options](const std::string& command_line) {
            return RunSweepCommand(*options, command_line);
          }};
}

int RunSweepCommand(const SweepCommandOptions& options, const std::string& command_line) {
  return RunCommand(kCommand, "", [&] { return Sweep(options, command_line); });
}

}  // namespace allanlab::app
