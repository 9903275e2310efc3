#include "experiments/aggregate.h"

#include <algorithm>
#include <cmath>

namespace allanlab::experiments {

const ColumnStats* PointStats::Find(const std::string& column) const {
  for (const ColumnStats& c : columns) {
    if (c.column == column) return &c;
  }
  return nullptr;
}

std::vector<PointStats> Aggregate(const RunSummary& run) {
  std::vector<PointStats> stats(run.columns.size());
  // Welford's update in trial order: one pass, stable for ratios near 1, deterministic.
  std::vector<std::vector<double>> m2(run.columns.size());
  std::vector<double> runtime_sum(run.columns.size(), 0.0);
  for (std::size_t p = 0; p < run.columns.size(); ++p) {
    stats[p].point = static_cast<int>(p);
    for (const std::string& name : run.columns[p]) stats[p].columns.push_back({name, 0, 0.0, 0.0, 0.0});
    m2[p].assign(run.columns[p].size(), 0.0);
  }
  for (const TrialRow& row : run.rows) {
    if (row.point < 0 || static_cast<std::size_t>(row.point) >= stats.size()) continue;
    PointStats& point = stats[static_cast<std::size_t>(row.point)];
    ++point.trials;
    runtime_sum[static_cast<std::size_t>(row.point)] += row.runtime_s;
    if (!row.ok) {
      ++point.failed;
      continue;
    }
    for (std::size_t c = 0; c < point.columns.size() && c < row.values.size(); ++c) {
      const double x = row.values[c];
      if (!std::isfinite(x)) continue;
      ColumnStats& s = point.columns[c];
      ++s.count;
      const double delta = x - s.mean;
      s.mean += delta / static_cast<double>(s.count);
      m2[static_cast<std::size_t>(row.point)][c] += delta * (x - s.mean);
    }
  }
  for (std::size_t p = 0; p < stats.size(); ++p) {
    PointStats& point = stats[p];
    if (point.trials > 0) point.mean_runtime_s = runtime_sum[p] / static_cast<double>(point.trials);
    for (std::size_t c = 0; c < point.columns.size(); ++c) {
      ColumnStats& s = point.columns[c];
      if (s.count == 0) {
        s.mean = std::nan("");
        s.std = std::nan("");
        s.standard_error = std::nan("");
      } else if (s.count == 1) {
        s.std = std::nan("");
        s.standard_error = std::nan("");
      } else {
        s.std = std::sqrt(m2[p][c] / static_cast<double>(s.count - 1));
        s.standard_error = s.std / std::sqrt(static_cast<double>(s.count));
      }
    }
  }
  return stats;
}

double CoverageStandardError(double nominal, std::int64_t n) {
  if (n <= 0) return std::nan("");
  return std::sqrt(nominal * (1.0 - nominal) / static_cast<double>(n));
}

RateInterval WilsonInterval(double rate, std::int64_t n, double z) {
  if (n <= 0) return {std::nan(""), std::nan("")};
  const double nd = static_cast<double>(n);
  const double z2 = z * z;
  const double centre = (rate + z2 / (2.0 * nd)) / (1.0 + z2 / nd);
  const double half = z * std::sqrt(rate * (1.0 - rate) / nd + z2 / (4.0 * nd * nd)) / (1.0 + z2 / nd);
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

std::string TargetVerdict(const RateInterval& interval, double target_low, double target_high) {
  if (!(interval.low <= interval.high)) return "undecided";
  if (interval.low >= target_low && interval.high <= target_high) return "met";
  if (interval.high < target_low || interval.low > target_high) return "not met";
  return "undecided";
}

}  // namespace allanlab::experiments
