#pragma once
// Stable32 result tables (NIST SP 1065 reference tier, tests/data/reference/*/SOURCE.txt) and the
// arithmetic Stable32 uses for their confidence intervals, so tests can compare at the printed
// precision.
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "estimators/confidence.h"

namespace allanlab::testing_support {

// One row: AF Tau # Alpha MinSigma Sigma MaxSigma (deviations, not variances).
struct Stable32Row {
  std::int64_t m = 0;
  double tau_s = 0.0;
  std::int64_t terms = 0;
  int alpha = 0;
  double min_sigma = 0.0, sigma = 0.0, max_sigma = 0.0;
};

// Rows of a Stable32 result file ('#' lines skipped). Throws std::runtime_error when the file
// cannot be read or a row does not parse.
std::vector<Stable32Row> ReadStable32Table(const std::string& path);

// First number of every non-comment line of a data file (PHASE.DAT, ocxo_frequency.txt).
std::vector<double> ReadDataColumn(const std::string& path);

// The interval Stable32 prints for a variance with `edf` degrees of freedom at 68.3 %. Up to
// EDF 100 it matches exact chi-square quantiles; above, Stable32's intervals are 0.5-0.7 % narrower
// and are reproduced to the printed digits by Wilson-Hilferty quantiles with z = Phi^-1(0.84)
// (the two-sided 68.3 % level with its tail rounded to 0.16). Found by fitting the PHASE.DAT and
// OCXO tables: every row with EDF > 100 (137 ... 12706) agrees to <= 5e-5 this way, rows up to
// EDF 98 agree with exact quantiles.
estimators::Interval Stable32Interval(double variance, double edf);

// |actual / expected - 1| <= tol, with both numbers and the error in the failure message.
::testing::AssertionResult NearRelative(const char* what, double actual, double expected,
                                        double tol);

// The row's MinSigma and MaxSigma equal Stable32's interval for `variance` with `edf` degrees of
// freedom, within the printed digits plus the residual of the interval arithmetic at small EDF:
// 1.5e-4 + 2e-3/EDF relative.
::testing::AssertionResult MatchesStable32Interval(double variance, double edf,
                                                   const Stable32Row& row);

}  // namespace allanlab::testing_support
