#pragma once
// Runs a sweep: every (point, trial) through a driver, OpenMP across trials (one parallel region,
// a workspace per thread made once), optionally MPI across ranks, with checkpoint/resume and
// progress. Deterministic: the rows, and so every table, are bit-identical for any thread count,
// rank count, batch size and for a resumed run (rows are kept by (point, trial) and aggregated in
// that order, never in completion order).
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "experiments/sweep_spec.h"
#include "experiments/trial_driver.h"

namespace allanlab::experiments {

struct TrialRow {
  int point = 0;
  std::int64_t trial = 0;
  bool ok = true;
  std::string status = "ok";  // "ok" or "failed: <reason>"
  double runtime_s = 0.0;     // wall time of Run (not part of determinism checks)
  std::vector<double> values;  // driver columns (NaN when failed)
};

struct RunnerOptions {
  int threads = 0;              // 0: OpenMP default
  std::int64_t batch_trials = 64;  // trials per checkpointed batch
  std::string checkpoint_path;  // empty: no checkpoint. Rows are appended per finished batch
                                // to this file, which records the spec hash.
  bool resume = false;          // continue from checkpoint_path (its spec hash must match)
  bool progress = false;        // force progress lines on stderr (default: only on a terminal)
  bool IsValid(std::string* why) const;
};

struct RunSummary {
  std::vector<std::vector<std::string>> columns;  // per point
  std::vector<TrialRow> rows;                     // sorted by (point, trial), all trials
  std::int64_t trials_resumed = 0;                // taken from the checkpoint, not recomputed
  std::int64_t trials_failed = 0;
  double wall_time_s = 0.0;
  bool ok = false;
  std::string message;
};

// Returns summary->ok. With MPI built in and several ranks, trials are split over ranks and the
// rows gathered on rank 0 (other ranks return ok with empty rows).
bool RunSweep(const SweepSpec& spec, const TrialDriver& driver, const RunnerOptions& options,
              RunSummary* summary);

}  // namespace allanlab::experiments
