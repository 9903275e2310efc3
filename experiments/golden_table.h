#pragma once
// The regression check's golden tables (`allanlab validate`): per sweep point and column, the
// trial count, mean and Monte Carlo standard error of a fixed sweep, written once and compared
// with every later run. The tolerance rule is written into each table: a number
// moved when |now - golden| > z sqrt(se_now^2 + se_golden^2); 0/1 columns take the
// binomial standard error with p kept 1/count away from 0 and 1; columns with se 0 must match to
// 1e-12 relative; a changed trial count is always a move.
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "experiments/aggregate.h"
#include "experiments/sweep_spec.h"

namespace allanlab::experiments {

// One number of a golden table, keyed by (point, column).
struct GoldenValue {
  std::int64_t count = 0;
  double mean = 0.0;
  double standard_error = 0.0;
};
using GoldenTable = std::map<std::pair<int, std::string>, GoldenValue>;

// Reads a table WriteGoldenTable wrote; *why names the file and line of the first problem.
bool ReadGoldenTable(const std::string& path, GoldenTable* table, std::string* why);

// Writes the table of `stats` atomically, after `provenance_lines` ('#' comment lines), the spec's
// name and hash, and the tolerance rule.
bool WriteGoldenTable(const std::string& path, const SweepSpec& spec, const std::vector<PointStats>& stats,
                      const std::string& provenance_lines, std::string* why);

// One line per number that moved beyond z standard errors, appeared or disappeared ("<name> point
// <p> <column>: ..."); empty when nothing moved. *compared counts the numbers compared.
std::vector<std::string> CompareWithGolden(const std::string& name, const GoldenTable& golden,
                                           const std::vector<PointStats>& stats, double z,
                                           std::int64_t* compared);

}  // namespace allanlab::experiments
