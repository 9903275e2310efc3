#pragma once
// What one Monte Carlo trial computes (thin drivers, docs/architecture.md "… an experiment"): a driver maps (sweep point,
// trial) to a flat row of numbers with named columns. The runner (runner.h) does threading,
// MPI, checkpointing and progress; the aggregation (aggregate.h) turns rows into per-column
// mean / std / standard error; each driver's report turns those into its validation table.
//
// Convention for columns, so aggregation stays generic:
//   * a per-trial estimate normalised by its exact expectation ("ratio") -> mean - 1 is the bias;
//   * indicator columns (0/1) -> their mean is a coverage or a failure rate;
//   * per-point constants (a predicted std, an exact expectation) repeated in every row.
// Column names are "<quantity>/<estimator or method>/<tau index or coefficient>", e.g.
// "avar_ratio/overlapping/m=16", "in_ci68/gr_edf/overlapping/m=16", "N_value/gls".
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "experiments/injected_fault.h"
#include "experiments/sweep_spec.h"

namespace allanlab::experiments {

// Per-thread scratch a driver reuses across trials (buffers, FFT plans, workspaces).
class TrialWorkspace {
 public:
  virtual ~TrialWorkspace() = default;
};

class TrialDriver {
 public:
  virtual ~TrialDriver() = default;
  // The columns every row of this point has, known before any trial runs.
  virtual std::vector<std::string> Columns(const SweepSpec& spec, const SweepPoint& point) const = 0;
  virtual std::unique_ptr<TrialWorkspace> MakeWorkspace() const = 0;
  // Runs one trial. Must be thread-safe given a workspace per thread, and deterministic in
  // (spec.seed, point.index, trial) only: random engines come from sim::MakeEngine-style hashing
  // of those (point.model.Generate(Hash(seed, point.index), trial, n)). Returns
  // Columns(...).size() values; throws std::exception for a failed trial (the runner records
  // it as a row with status "failed: <what>", never drops it).
  virtual std::vector<double> Run(const SweepSpec& spec, const SweepPoint& point,
                                  std::int64_t trial, TrialWorkspace* workspace) const = 0;
};

// A driver that applies an InjectedFault to the estimates it takes (the identity by default).
class FaultInjectableDriver : public TrialDriver {
 public:
  FaultInjectableDriver() = default;
  explicit FaultInjectableDriver(InjectedFault fault) : fault_(fault) {}

 protected:
  InjectedFault fault_;
};

// The seed a point's records are generated from: splitmix64 of (spec seed, point index), so
// adding a point to a sweep does not change the records of the others.
std::uint64_t PointSeed(std::uint64_t spec_seed, int point_index);

}  // namespace allanlab::experiments
