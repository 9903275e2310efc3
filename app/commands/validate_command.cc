#include "app/commands/validate_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <vector>

#include "app/reports/atomic_file.h"
#include "app/reports/provenance.h"
#include "experiments/aggregate.h"
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

struct GoldenValue {
  std::int64_t count = 0;
  double mean = 0.0;
  double standard_error = 0.0;
};
using GoldenTable = std::map<std::pair<int, std::string>, GoldenValue>;

std::string Exact(double value) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

std::string Short(double value) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

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

bool ReadGolden(const fs::path& path, GoldenTable* table, std::string* why) {
  std::ifstream in(path);
  if (!in) {
    *why = "no golden table " + path.string() + " (create it with allanlab validate --update)";
    return false;
  }
  std::string line;
  int line_number = 0;
  bool header = false;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.empty() || line[0] == '#') continue;
    if (!header) {
      header = true;
      if (line != "point,column,count,mean,standard_error") {
        *why = path.string() + ":" + std::to_string(line_number) + ": unexpected header";
        return false;
      }
      continue;
    }
    std::istringstream fields(line);
    std::string point, column, count, mean, se;
    if (!std::getline(fields, point, ',') || !std::getline(fields, column, ',') ||
        !std::getline(fields, count, ',') || !std::getline(fields, mean, ',') ||
        !std::getline(fields, se, ',')) {
      *why = path.string() + ":" + std::to_string(line_number) + ": expected 5 fields";
      return false;
    }
    try {
      (*table)[{std::stoi(point), column}] = {std::stoll(count), std::stod(mean), std::stod(se)};
    } catch (const std::exception&) {
      *why = path.string() + ":" + std::to_string(line_number) + ": bad number";
      return false;
    }
  }
  return true;
}

// 0/1 columns (interval coverage, failure and found indicators): their mean is a rate.
bool IsRateColumn(const std::string& column) {
  return column.rfind("in_ci", 0) == 0 || column.rfind("missing/", 0) == 0 ||
         column.rfind("failed/", 0) == 0 || column.rfind("converged/", 0) == 0 ||
         column.find("found/") != std::string::npos;
}

// The Monte Carlo standard error a comparison uses (kToleranceRule states it in every golden
// table). A rate gets the binomial sqrt(p (1 - p) / n) with p kept 1/n away from 0 and 1, so
// that "all 40 trials covered" still tolerates a flip or two rather than none.
double StandardError(const std::string& column, std::int64_t count, double mean, double se) {
  if (IsRateColumn(column) && count > 0 && std::isfinite(mean)) {
    const double n = static_cast<double>(count);
    const double p = std::clamp(mean, 1.0 / n, 1.0 - 1.0 / n);
    return p > 0.0 && p < 1.0 ? std::sqrt(p * (1.0 - p) / n) : 0.0;
  }
  return std::isfinite(se) ? se : 0.0;
}

constexpr const char* kToleranceRule =
    "# tolerance: a number moved when |now - golden| > z sqrt(se_now^2 + se_golden^2) (z = 5 unless\n"
    "#   --z), se = its Monte Carlo standard error: sample std / sqrt(count) for a mean over trials;\n"
    "#   binomial sqrt(p (1 - p) / count), p kept >= 1/count from 0 and 1, for 0/1 columns (in_ci*,\n"
    "#   missing/, failed/, converged/, *found/); columns with se 0 (exact constants such as\n"
    "#   edf_exact) must match to 1e-12 relative. A changed trial count is always a move.\n";

bool WriteGolden(const fs::path& path, const experiments::SweepSpec& spec,
                 const std::vector<experiments::PointStats>& stats, const Provenance& provenance,
                 std::string* why) {
  AtomicFile out;
  if (!out.Open(path.string(), why)) return false;
  out.stream() << ProvenanceCommentLines(provenance) << "# spec: " << spec.name << " (hash "
               << std::hex << spec.Hash() << std::dec << ")\n"
               << kToleranceRule << "point,column,count,mean,standard_error\n";
  for (const experiments::PointStats& point : stats) {
    for (const experiments::ColumnStats& c : point.columns) {
      out.stream() << point.point << ',' << c.column << ',' << c.count << ',' << Exact(c.mean) << ','
                   << Exact(c.standard_error) << '\n';
    }
  }
  return out.Commit(why);
}

// Lines describing what moved; empty when nothing did.
std::vector<std::string> Compare(const std::string& name, const GoldenTable& golden,
                                 const std::vector<experiments::PointStats>& stats, double z,
                                 std::int64_t* compared) {
  std::vector<std::string> moved;
  GoldenTable seen;
  for (const experiments::PointStats& point : stats) {
    for (const experiments::ColumnStats& c : point.columns) {
      const auto key = std::make_pair(point.point, c.column);
      seen[key] = {};
      std::ostringstream where;
      where << name << " point " << point.point << ' ' << c.column;
      const auto it = golden.find(key);
      if (it == golden.end()) {
        moved.push_back(where.str() + ": new (not in the golden table)");
        continue;
      }
      ++*compared;
      const GoldenValue& g = it->second;
      const bool both_nan = std::isnan(g.mean) && std::isnan(c.mean);
      const double se_now = StandardError(c.column, c.count, c.mean, c.standard_error);
      const double se_old = StandardError(c.column, g.count, g.mean, g.standard_error);
      const double diff = c.mean - g.mean;
      const double tolerance = z * std::sqrt(se_now * se_now + se_old * se_old) +
                               1e-12 * std::max(std::abs(c.mean), std::abs(g.mean));
      if (g.count != c.count) {
        moved.push_back(where.str() + ": " + std::to_string(c.count) + " trials counted, golden " +
                        std::to_string(g.count));
      } else if (!both_nan && !(std::abs(diff) <= tolerance)) {
        const double sigma = std::sqrt(se_now * se_now + se_old * se_old);
        moved.push_back(where.str() + ": " + Short(c.mean) + " +- " + Short(se_now) + ", golden " +
                        Short(g.mean) + " +- " + Short(se_old) + " (" +
                        (sigma > 0 ? Short(diff / sigma) + " sigma" : std::string("exact value")) +
                        ")");
      }
    }
  }
  for (const auto& [key, value] : golden) {
    if (!seen.count(key)) {
      moved.push_back(name + " point " + std::to_string(key.first) + ' ' + key.second +
                      ": gone (in the golden table only)");
    }
  }
  return moved;
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
      if (!WriteGolden(golden_path, spec, stats, provenance, &why)) return RuntimeFailure(why);
      std::cout << "validate: wrote " << golden_path.string() << " (" << run.wall_time_s << " s)\n";
      continue;
    }
    GoldenTable golden;
    if (!ReadGolden(golden_path, &golden, &why)) return RuntimeFailure(why);
    std::int64_t here = 0;
    const std::vector<std::string> lines = Compare(spec.name, golden, stats, options.z, &here);
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
                          std::to_string(compared) + " numbers moved beyond " + Short(options.z) +
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
