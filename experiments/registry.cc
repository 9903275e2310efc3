#include "experiments/registry.h"

#include <algorithm>
#include <memory>
#include <type_traits>

#include "experiments/avar_bias.h"
#include "experiments/avar_error_bars.h"
#include "experiments/coefficient_recovery.h"
#include "experiments/default_intervals.h"
#include "experiments/estimator_coverage.h"
#include "experiments/record_length.h"
#include "experiments/seed_paper.h"

namespace allanlab::experiments {
namespace {

struct Entry {
  const char* name;
  std::unique_ptr<Experiment> (*make)(const InjectedFault&);
};

// Experiments with no fault to inject (their numbers are not in the regression check's golden
// tables) are made without one.
template <typename T>
std::unique_ptr<Experiment> Make(const InjectedFault& fault) {
  if constexpr (std::is_constructible_v<T, InjectedFault>) {
    return std::make_unique<T>(fault);
  } else {
    (void)fault;
    return std::make_unique<T>();
  }
}

constexpr Entry kExperiments[] = {
    {"avar_bias", &Make<AvarBiasExperiment>},
    {"avar_error_bars", &Make<AvarErrorBarsExperiment>},
    {"coefficient_recovery", &Make<CoefficientRecoveryExperiment>},
    {"default_intervals", &Make<DefaultIntervalsExperiment>},
    {"estimator_coverage", &Make<EstimatorCoverageExperiment>},
    {"record_length", &Make<RecordLengthExperiment>},
    {"seed_paper", &Make<SeedPaperExperiment>},
};

}  // namespace

std::vector<std::string> ExperimentNames() {
  std::vector<std::string> names;
  for (const Entry& e : kExperiments) names.emplace_back(e.name);
  std::sort(names.begin(), names.end());
  return names;
}

std::unique_ptr<Experiment> MakeExperiment(std::string_view name, const InjectedFault& fault) {
  for (const Entry& e : kExperiments) {
    if (name == e.name) return e.make(fault);
  }
  return nullptr;
}

}  // namespace allanlab::experiments
