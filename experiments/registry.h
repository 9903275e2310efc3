#pragma once
// The experiments allanlab ships, by name (the sweep spec's `driver:`).
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "experiments/experiment.h"
#include "experiments/injected_fault.h"

namespace allanlab::experiments {

std::vector<std::string> ExperimentNames();  // sorted
// nullptr when unknown (the caller lists ExperimentNames() in its message). `fault`: only tests
// of the regression check pass anything but the default (injected_fault.h).
std::unique_ptr<Experiment> MakeExperiment(std::string_view name, const InjectedFault& fault = {});

}  // namespace allanlab::experiments
