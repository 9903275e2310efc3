#include "experiments/runner.h"

#include <omp.h>
#include <sys/stat.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "experiments/checkpoint_store.h"
#include "experiments/mpi_world.h"
#include "experiments/progress.h"

namespace allanlab::experiments {
namespace {

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

// The checkpoint file of this rank: the path itself for one process, "<path>.rank<r>of<n>"
// for several (each rank appends only its own batches).
std::string RankCheckpointPath(const std::string& path, const RankInfo& ranks) {
  if (ranks.size == 1) return path;
  return path + ".rank" + std::to_string(ranks.rank) + "of" + std::to_string(ranks.size);
}

TrialRow RunTrial(const SweepSpec& spec, const TrialDriver& driver, const SweepPoint& point,
                  std::size_t num_columns, std::int64_t trial, TrialWorkspace* workspace) {
  TrialRow row;
  row.point = point.index;
  row.trial = trial;
  const auto start = std::chrono::steady_clock::now();
  try {
    row.values = driver.Run(spec, point, trial, workspace);
    if (row.values.size() != num_columns) {
      throw std::runtime_error("the driver returned " + std::to_string(row.values.size()) +
                               " values for " + std::to_string(num_columns) + " columns");
    }
  } catch (const std::exception& e) {
    row.ok = false;
    row.status = "failed: ";
    row.status += e.what();
  } catch (...) {
    row.ok = false;
    row.status = "failed: unknown exception";
  }
  if (!row.ok) row.values.assign(num_columns, std::numeric_limits<double>::quiet_NaN());
  row.runtime_s = Seconds(start);
  return row;
}

}  // namespace

bool RunnerOptions::IsValid(std::string* why) const {
  if (threads < 0) {
    if (why) *why = "threads must be >= 0 (0: the OpenMP default)";
    return false;
  }
  if (batch_trials < 1) {
    if (why) *why = "batch_trials must be >= 1";
    return false;
  }
  if (resume && checkpoint_path.empty()) {
    if (why) *why = "resume needs a checkpoint path";
    return false;
  }
  return true;
}

bool RunSweep(const SweepSpec& spec, const TrialDriver& driver, const RunnerOptions& options,
              RunSummary* summary) {
  const auto start = std::chrono::steady_clock::now();
  *summary = RunSummary{};
  auto fail = [&](std::string message) {
    summary->ok = false;
    summary->message = std::move(message);
    summary->wall_time_s = Seconds(start);
    return false;
  };
  std::string why;
  if (!options.IsValid(&why)) return fail(why);
  if (spec.trials < 1 || spec.points.empty()) return fail("the sweep has no trials to run");
  const RankInfo ranks = CurrentRanks();

  // Columns are known before any trial runs.
  try {
    for (const SweepPoint& point : spec.points) summary->columns.push_back(driver.Columns(spec, point));
  } catch (const std::exception& e) {
    return fail(std::string("the driver cannot name its columns: ") + e.what());
  }

  // Slot (point, trial) -> index point * trials + trial; batches are runs of consecutive slots,
  // rank r owning batches r, r + size, ...
  const std::int64_t trials = spec.trials;
  const std::int64_t total = static_cast<std::int64_t>(spec.points.size()) * trials;
  const std::int64_t batch = options.batch_trials;
  const std::int64_t num_batches = (total + batch - 1) / batch;
  std::vector<TrialRow> slots(static_cast<std::size_t>(total));
  std::vector<char> done(static_cast<std::size_t>(total), 0);

  CheckpointStore store;
  const bool checkpointing = !options.checkpoint_path.empty();
  if (checkpointing) {
    const std::string path = RankCheckpointPath(options.checkpoint_path, ranks);
    std::vector<TrialRow> resumed;
    bool opened = false;
    struct stat st;
    // A run killed before its store existed simply starts over.
    if (options.resume && ::stat(path.c_str(), &st) == 0) {
      opened = store.Resume(path, spec.Hash(), spec.driver, &resumed, &why);
    } else {
      opened = store.Create(path, spec.Hash(), spec.driver, &why);
    }
    if (!AllRanksOk(opened)) return fail(opened ? "another rank could not open its checkpoint" : why);
    for (TrialRow& row : resumed) {
      if (row.point < 0 || row.point >= static_cast<int>(spec.points.size()) || row.trial < 0 ||
          row.trial >= trials ||
          row.values.size() != summary->columns[static_cast<std::size_t>(row.point)].size()) {
        return fail("checkpoint " + path + " holds a row that does not fit this sweep");
      }
      const std::size_t slot = static_cast<std::size_t>(row.point * trials + row.trial);
      if (!done[slot]) ++summary->trials_resumed;
      done[slot] = 1;
      slots[slot] = std::move(row);
    }
  }

  // This rank's pending work, in slot order, and the count still missing per batch.
  std::vector<std::int64_t> pending;
  std::vector<std::atomic<std::int64_t>> missing(static_cast<std::size_t>(num_batches));
  for (std::int64_t b = ranks.rank; b < num_batches; b += ranks.size) {
    std::int64_t count = 0;
    for (std::int64_t s = b * batch; s < std::min(total, (b + 1) * batch); ++s) {
      if (!done[static_cast<std::size_t>(s)]) {
        pending.push_back(s);
        ++count;
      }
    }
    missing[static_cast<std::size_t>(b)].store(count);
  }

  const bool show_progress = ranks.rank == 0 && (options.progress || StderrIsTerminal());
  ProgressMeter progress(show_progress, static_cast<std::int64_t>(pending.size()) * ranks.size,
                         summary->trials_resumed * ranks.size);
  std::mutex store_mutex;
  std::atomic<std::int64_t> computed{0};
  std::atomic<bool> aborted{false};
  std::string store_error;
  const std::int64_t num_pending = static_cast<std::int64_t>(pending.size());

  const int threads = options.threads > 0 ? options.threads : omp_get_max_threads();
  std::string workspace_error;
#pragma omp parallel num_threads(threads)
  {
    std::unique_ptr<TrialWorkspace> workspace;
    bool have_workspace = true;
    try {
      workspace = driver.MakeWorkspace();
    } catch (const std::exception& e) {
      have_workspace = false;
#pragma omp critical(allanlab_runner_error)
      workspace_error = e.what();
      aborted.store(true);
    }
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t i = 0; i < num_pending; ++i) {
      if (!have_workspace || aborted.load(std::memory_order_relaxed)) continue;
      const std::int64_t slot = pending[static_cast<std::size_t>(i)];
      const std::int64_t point_index = slot / trials;
      const SweepPoint& point = spec.points[static_cast<std::size_t>(point_index)];
      slots[static_cast<std::size_t>(slot)] =
          RunTrial(spec, driver, point, summary->columns[static_cast<std::size_t>(point_index)].size(),
                   slot % trials, workspace.get());
      const std::int64_t b = slot / batch;
      // The thread that finishes a batch stores it: acq_rel makes the other threads' rows of
      // the batch visible here.
      if (missing[static_cast<std::size_t>(b)].fetch_sub(1, std::memory_order_acq_rel) == 1) {
        std::lock_guard<std::mutex> lock(store_mutex);
        if (checkpointing && !aborted.load()) {
          std::vector<TrialRow> rows;
          for (std::int64_t s = b * batch; s < std::min(total, (b + 1) * batch); ++s) {
            if (!done[static_cast<std::size_t>(s)]) rows.push_back(slots[static_cast<std::size_t>(s)]);
          }
          std::string error;
          if (!store.Append(rows, &error)) {
            store_error = error;
            aborted.store(true);
          }
        }
        progress.Update(computed.fetch_add(1) + 1);
      } else {
        computed.fetch_add(1);
      }
    }
  }
  progress.Finish(computed.load());
  store.Close();
  if (!workspace_error.empty()) {
    AllRanksOk(false);
    return fail("the driver cannot make its workspace: " + workspace_error);
  }
  if (!store_error.empty()) {
    AllRanksOk(false);
    return fail(store_error);
  }
  if (!AllRanksOk(true)) return fail("another rank failed");

  // This rank's rows (computed or resumed) in slot order; rank 0 gathers the others'.
  std::vector<TrialRow> rows;
  for (std::int64_t b = ranks.rank; b < num_batches; b += ranks.size) {
    for (std::int64_t s = b * batch; s < std::min(total, (b + 1) * batch); ++s) {
      rows.push_back(std::move(slots[static_cast<std::size_t>(s)]));
    }
  }
  if (!GatherRowsToRoot(&rows, &why)) return fail(why);
  if (ranks.rank == 0) {
    std::sort(rows.begin(), rows.end(), [](const TrialRow& a, const TrialRow& b) {
      return a.point != b.point ? a.point < b.point : a.trial < b.trial;
    });
    if (static_cast<std::int64_t>(rows.size()) != total) {
      return fail("gathered " + std::to_string(rows.size()) + " rows of " + std::to_string(total));
    }
    for (const TrialRow& row : rows) summary->trials_failed += row.ok ? 0 : 1;
    summary->rows = std::move(rows);
  }
  summary->ok = true;
  summary->wall_time_s = Seconds(start);
  return true;
}

}  // namespace allanlab::experiments
