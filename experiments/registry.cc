#include "experiments/registry.h"

#include "experiments/avar_error_bars.h"
#include "experiments/seed_paper.h"

namespace allanlab::experiments {

std::vector<std::string> ExperimentNames() { return {"avar_error_bars", "seed_paper"}; }

std::unique_ptr<Experiment> MakeExperiment(std::string_view name) {
  if (name == "avar_error_bars") return std::make_unique<AvarErrorBarsExperiment>();
  if (name == "seed_paper") return std::make_unique<SeedPaperExperiment>();
  return nullptr;
}

}  // namespace allanlab::experiments
