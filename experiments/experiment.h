#pragma once
// A validation experiment = a trial driver + the report that turns its aggregated rows into
// tables (CSV for machines + Markdown for people, same content) and plots. The registry
// (experiments/registry.h) maps the spec's `driver:` name to one of these.
#include <memory>
#include <string>
#include <vector>

#include "experiments/aggregate.h"
#include "experiments/runner.h"
#include "experiments/sweep_spec.h"
#include "experiments/trial_driver.h"

namespace allanlab::experiments {

// What every table carries (its provenance, docs/architecture.md "Conventions") and where it goes.
struct ReportContext {
  std::string output_dir;      // e.g. results/validation; created if missing
  std::string git_sha;         // of the built commit
  std::string build_type;
  std::string command_line;    // the one command that regenerates the table
  std::string date_utc;        // ISO 8601
  int threads = 1;
  int ranks = 1;
  double wall_time_s = -1.0;   // of the sweep, when known (< 0: not stated)
};

class Experiment {
 public:
  virtual ~Experiment() = default;
  virtual std::string Name() const = 0;  // == spec.driver
  // The question, method, reference and pass criterion, one paragraph (goes into the report).
  virtual std::string Question() const = 0;
  virtual const TrialDriver& Driver() const = 0;
  // Writes <output_dir>/<spec.name>.csv and .md (and plots); every file is written to a
  // temporary and renamed into place, so a failure leaves earlier files intact. Returns false
  // with *why on failure.
  virtual bool WriteReport(const SweepSpec& spec, const RunSummary& run,
                           const std::vector<PointStats>& stats, const ReportContext& context,
                           std::string* why) const = 0;
};

// An experiment whose trials one driver of type D runs, made with the fault (injected_fault.h)
// the driver applies when D takes one.
template <class D>
class DriverExperiment : public Experiment {
 public:
  template <class... Fault>
  explicit DriverExperiment(Fault... fault) : driver_(fault...) {}
  const TrialDriver& Driver() const final { return driver_; }

 private:
  D driver_;
};

}  // namespace allanlab::experiments
