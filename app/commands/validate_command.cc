#include "app/commands/validate_command.h"

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <vector>

#include "app/reports/provenance.h"
#include "common/number_text.h"
#include "experiments/aggregate.h"
#include "experiments/golden_table.h"
#include "experiments/registry.h"
#include "experiments/runner.h"
#include "experiments/sweep_spec.h"

#ifndef ALLANLAB_SOURCE_DIR
#define ALLANLAB_SOURCE_DIR "."
#endif

namespace allanlab::app {
namespace {

namespace fs = std::filesystem;
constexpr const char* kCommand = "validate";

std::vector<fs::path> SpecFiles(const std::string& dir, bool quick, std::string* why) {
  std::vector<fs::path> files;
  for (const char* sub : {"quick", "full"}) {
    if (quick && std::string(sub) == "full") continue;
    std::error_code ec;
    const fs::path folder = fs::path(dir) / sub;
    if (!fs::is_directory(folder, ec)) continue;
    for (const auto& entry : fs::directory_iterator(folder, ec)) {
      if (entry.path().extension() == ".yaml") files.push_back(entry.path());
    }
  }
  std::sort(files.begin(), files.end());
  if (files.empty()) *why = "no sweep specs (*.yaml) under " + dir + "/quick" + (quick ? "" : " or /full");
  return files;
}

std::optional<CommandFailure> Validate(const ValidateCommandOptions& options,
                                       const std::string& command_line) {
  if (options.threads < 0) return UsageFailure("--threads must be >= 0 (0: all cores)");
  if (!(options.z > 0.0)) return UsageFailure("--z must be > 0");
  const std::string specs_dir =
      options.specs_dir.empty() ? std::string(ALLANLAB_SOURCE_DIR) + "/experiments/specs/validate"
                                : options.specs_dir;
  const std::string golden_dir =
      options.golden_dir.empty() ? std::string(ALLANLAB_SOURCE_DIR) + "/tests/data/validate_quick"
                                 : options.golden_dir;
  std::string why;
  const std::vector<fs::path> files = SpecFiles(specs_dir, options.quick, &why);
  if (files.empty()) return UsageFailure(why);
  // Every spec is checked before any runs.
  std::vector<experiments::SweepSpec> specs(files.size());
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (!experiments::LoadSweepSpecFile(files[i].string(), &specs[i], &why)) return UsageFailure(why);
  }
  std::int64_t compared = 0;
  std::vector<std::string> moved;
  for (const experiments::SweepSpec& spec : specs) {
    const std::unique_ptr<experiments::Experiment> experiment = experiments::MakeExperiment(spec.driver, options.fault);
    if (!experiment) return UsageFailure("no experiment \"" + spec.driver + "\"");
    experiments::RunnerOptions runner;
    runner.threads = options.threads;
    experiments::RunSummary run;
    if (!experiments::RunSweep(spec, experiment->Driver(), runner, &run)) {
      return RuntimeFailure(spec.name + ": " + run.message);
    }
    const std::vector<experiments::PointStats> stats = experiments::Aggregate(run);
    const fs::path golden_path = fs::path(golden_dir) / (spec.name + ".csv");
    if (options.update) {
      std::error_code ec;
      fs::create_directories(golden_dir, ec);
      Provenance provenance = MakeProvenance(kCommand, command_line);
      if (!experiments::WriteGoldenTable(golden_path.string(), spec, stats, ProvenanceCommentLines(provenance), &why)) return RuntimeFailure(why);
      std::cout << "validate: wrote " << golden_path.string() << " (" << run.wall_time_s << " s)\n";
      continue;
    }
    experiments::GoldenTable golden;
    if (!experiments::ReadGoldenTable(golden_path.string(), &golden, &why)) return RuntimeFailure(why);
    std::int64_t here = 0;
    const std::vector<std::string> lines = experiments::CompareWithGolden(spec.name, golden, stats, options.z, &here);
    compared += here;
    std::cout << "validate " << spec.name << ": " << here << " numbers compared, " << lines.size()
              << " moved (" << run.wall_time_s << " s)\n";
    for (const std::string& line : lines) std::cout << "  moved: " << line << '\n';
    moved.insert(moved.end(), lines.begin(), lines.end());
  }
  std::cout << std::flush;
  if (options.update) return std::nullopt;
  if (!moved.empty()) {
    return RuntimeFailure("regression: " + std::to_string(moved.size()) + " of " +
                          std::to_string(compared) + " numbers moved beyond " + SignificantDigits(options.z, 6) +
                          " standard errors (listed above)");
  }
  std::cout << "validate: ok, " << compared << " numbers within " << options.z
            << " standard errors of the golden tables\n";
  return std::nullopt;
}

}  // namespace

Subcommand AddValidateCommand(CLI::App* parent) {
  auto options = std::make_shared<ValidateCommandOptions>();
  CLI::App* cmd = parent->add_subcommand(
      kCommand,
      "Regression check: rerun the fixed sweep points of experiments/specs/validate and compare "
      "every number with the golden tables (z = 5 on the Monte Carlo error).");
  cmd->add_flag("--quick", options->quick, "only the quick set (about 20 s of CPU on 2 cores)");
  cmd->add_flag("--update", options->update, "rewrite the golden tables instead of comparing");
  cmd->add_option("--specs", options->specs_dir, "spec folder (default: the source tree's)")
      ->type_name("DIR");
  cmd->add_option("--golden", options->golden_dir, "golden-table folder (default: the source tree's)")
      ->type_name("DIR");
  cmd->add_option("--threads", options->threads, "OpenMP threads (default 0: all cores)")
      ->type_name("N");
  cmd->add_option("--z", options->z, "standard errors a number may move (default 5)")->type_name("Z");
  cmd->footer("Exit status: 0 nothing moved, 1 a regression (or a run failure), 2 usage error.");
  return {cmd, [options](const std::string& command_line) {
            return RunValidateCommand(*options, command_line);
          }};
}

int RunValidateCommand(const ValidateCommandOptions& options, const std::string& command_line) {
  return RunCommand(kCommand, "", [&] { return Validate(options, command_line); });
}

}  // namespace allanlab::app
