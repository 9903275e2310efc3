#pragma once
// Per point and per column: count, mean, sample std and standard error of the mean over the
// successful trials, summed in trial order (deterministic). Failed trials count in failure_rate.
#include <string>
#include <vector>

#include "experiments/runner.h"

namespace allanlab::experiments {

struct ColumnStats {
  std::string column;
  std::int64_t count = 0;  // successful trials with a finite value
  double mean = 0.0;
  double std = 0.0;         // sample standard deviation (n - 1)
  double standard_error = 0.0;  // std / sqrt(count)
};

struct PointStats {
  int point = 0;
  std::int64_t trials = 0;
  std::int64_t failed = 0;
  double mean_runtime_s = 0.0;
  std::vector<ColumnStats> columns;  // in the driver's column order
  const ColumnStats* Find(const std::string& column) const;  // nullptr when absent
};

std::vector<PointStats> Aggregate(const RunSummary& run);

// Binomial standard error of an observed coverage p over n trials: sqrt(p (1 - p) / n), with
// p replaced by the nominal level when given (so 0 or 1 observed still has an error bar).
double CoverageStandardError(double nominal, std::int64_t n);

// Wilson score interval (95 % by default, z = 1.96) of a proportion observed as `rate` over n
// trials; {NaN, NaN} when n <= 0.
struct RateInterval {
  double low = 0.0, high = 0.0;
};
RateInterval WilsonInterval(double rate, std::int64_t n, double z = 1.96);

// "met" when the whole interval lies inside [target_low, target_high], "not met" when the whole
// interval lies outside it, else "undecided" (the trials cannot tell).
std::string TargetVerdict(const RateInterval& interval, double target_low, double target_high);

}  // namespace allanlab::experiments
