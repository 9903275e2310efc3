#include "experiments/registry.h"

namespace allanlab::experiments {

std::vector<std::string> ExperimentNames() { return {}; }

std::unique_ptr<Experiment> MakeExperiment(std::string_view /*name*/) { return nullptr; }

}  // namespace allanlab::experiments
