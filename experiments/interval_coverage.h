#pragma once
// One cell of an interval-coverage table: for each confidence level, whether the interval
// ComputeAvar's rule gives an Allan point at that level (estimators::PointInterval) holds the
// expected value (1 or 0), NaN when the point is missing or has no EDF. Shared by the
// default_intervals and estimator_coverage tables.
#include <limits>
#include <vector>

#include "estimators/avar.h"

namespace allanlab::experiments {

inline void AppendCoverageHits(const estimators::AvarSummary& summary,
                               const estimators::AvarPoint* point, double expected,
                               const std::vector<double>& levels, std::vector<double>* row) {
  for (double level : levels) {
    if (!point || !(point->edf > 0.0)) {
      row->push_back(std::numeric_limits<double>::quiet_NaN());
      continue;
    }
    const estimators::Interval ci = estimators::PointInterval(summary, *point, level);
    row->push_back(ci.low <= expected && expected <= ci.high ? 1.0 : 0.0);
  }
}

}  // namespace allanlab::experiments
