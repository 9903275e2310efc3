#pragma once
// A published Allan curve read as the fitting and diagnosis code take it: a text table ('#'
// comments; ',', tab, ';' or whitespace columns; plain, gzip or xz; '-' for standard input) with a
// header naming the tau column (tau_s, tau) and the curve's column. A column whose name starts
// with "avar", "oavar" or "var" holds Allan variances in unit^2; any other holds deviations in
// unit. Published curves carry neither the record length nor the sample period, so both are
// given: the averaging factor of each row is m = round(tau / tau0).
//
// Rows are kept in file order when m >= 1, m rises and 2m <= N (the overlapping estimator's
// range); a row outside that range is skipped and counted (CurveTable::skipped names why). A
// value that is not a number or not finite and > 0 is an error with its line.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "app/input/rate_units.h"
#include "estimators/fit/fit_avar_model.h"

namespace allanlab::app {

struct CurveTableOptions {
  std::string path;
  std::string column = "adev_x";
  RateUnit unit = RateUnit::kDegPerHour;
  double record_length_s = 0.0;  // > 0
  double sample_rate_hz = 0.0;   // > 0
};

struct CurveTable {
  estimators::AvarCurve curve;  // overlapping AVAR in (rad/s)^2; EDFs of white noise (seeds only)
  bool variance = false;        // the column held variances
  std::int64_t rows = 0;        // data rows read
  std::vector<std::string> skipped;  // one line per skipped row ("line 12: tau 5000 s beyond ...")
};

// Reads the table. Failures: exit code and one line, starting with the path.
struct CurveTableError {
  int exit_code = 0;
  std::string message;
};
bool ReadCurveTable(const CurveTableOptions& options, CurveTable* table, CurveTableError* error);

}  // namespace allanlab::app
