#pragma once
// The pieces of the `_allanlab` extension module (python/module.cc). Each function returns what
// the command of the same name computes, through the command's own steps (app/*_command.h); the
// Python package (python/allanlab/) turns the results into numpy arrays and result classes.
// Errors raise ValueError (what `allanlab` reports as a usage error, exit 2) or RuntimeError
// (exit 1), with the command's one-line message.
#include <pybind11/pybind11.h>

#include <string>

namespace allanlab::python {

// simulate(preset | sensor, duration_s, seed, trial, rate_hz) -> (rate in rad/s, info dict),
// expected_oavar(preset | sensor, rate_hz, m list, num_samples) -> list.
void AddRecordFunctions(pybind11::module_& m);
// avar, fit, diagnose on a record in memory -> the command's JSON (a str).
void AddCurveFunctions(pybind11::module_& m);

// Raises the exception for a command's exit code (kExitUsageError: ValueError, else RuntimeError).
[[noreturn]] void Raise(int exit_code, const std::string& message);

}  // namespace allanlab::python
