#pragma once
// The experiments allanlab ships, by name (the sweep spec's `driver:`).
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "experiments/experiment.h"

namespace allanlab::experiments {

std::vector<std::string> ExperimentNames();  // sorted
// nullptr when unknown (the caller lists ExperimentNames() in its message).
std::unique_ptr<Experiment> MakeExperiment(std::string_view name);

}  // namespace allanlab::experiments
