#pragma once
// Helpers for the experiment tests: run a driver's trials directly and aggregate them the way
// experiments/aggregate.h specifies (mean, sample std, standard error over finite values).
#include <cmath>
#include <unistd.h>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "experiments/aggregate.h"
#include "experiments/trial_driver.h"

namespace allanlab::testing_support {

struct DriverRun {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;  // [trial][column]
  std::vector<double> Column(const std::string& name) const {
    std::vector<double> out;
    for (std::size_t c = 0; c < columns.size(); ++c) {
      if (columns[c] != name) continue;
      for (const auto& row : rows) out.push_back(row[c]);
    }
    return out;
  }
};

inline DriverRun RunTrials(const experiments::TrialDriver& driver, const experiments::SweepSpec& spec,
                           const experiments::SweepPoint& point, std::int64_t trials) {
  DriverRun run;
  run.columns = driver.Columns(spec, point);
  auto workspace = driver.MakeWorkspace();
  for (std::int64_t t = 0; t < trials; ++t) run.rows.push_back(driver.Run(spec, point, t, workspace.get()));
  return run;
}

inline experiments::PointStats Stats(const DriverRun& run, int point) {
  experiments::PointStats stats;
  stats.point = point;
  stats.trials = static_cast<std::int64_t>(run.rows.size());
  for (std::size_t c = 0; c < run.columns.size(); ++c) {
    experiments::ColumnStats s;
    s.column = run.columns[c];
    double sum = 0.0, sum2 = 0.0;
    for (const auto& row : run.rows) {
      if (!std::isfinite(row[c])) continue;
      ++s.count;
      sum += row[c];
    }
    if (s.count > 0) s.mean = sum / static_cast<double>(s.count);
    for (const auto& row : run.rows) {
      if (std::isfinite(row[c])) sum2 += (row[c] - s.mean) * (row[c] - s.mean);
    }
    if (s.count > 1) {
      s.std = std::sqrt(sum2 / static_cast<double>(s.count - 1));
      s.standard_error = s.std / std::sqrt(static_cast<double>(s.count));
    }
    stats.columns.push_back(s);
  }
  return stats;
}

// An empty folder under the temp directory, removed with everything in it when the object goes:
// a report test must not leave its files behind on the machine.
class ScratchDirectory {
 public:
  explicit ScratchDirectory(const std::string& name) {
    // With the process id: two checkouts' suites running at once must not share a folder.
    path_ = std::filesystem::temp_directory_path() / name;
    path_ += "_";
    path_ += std::to_string(::getpid());
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;
  std::string path() const { return path_.string(); }

 private:
  std::filesystem::path path_;
};

}  // namespace allanlab::testing_support
