#include "experiments/golden_table.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/atomic_file.h"
#include "common/number_text.h"

namespace allanlab::experiments {
namespace {

// 0/1 columns (interval coverage, failure and found indicators): their mean is a rate.
bool IsRateColumn(const std::string& column) {
  return column.rfind("in_ci", 0) == 0 || column.rfind("missing/", 0) == 0 ||
         column.rfind("failed/", 0) == 0 || column.rfind("converged/", 0) == 0 ||
         column.find("found/") != std::string::npos;
}

// The Monte Carlo standard error a comparison uses (kToleranceRule states it in every golden
// table). A rate gets the binomial sqrt(p (1 - p) / n) with p kept 1/n away from 0 and 1, so
// that "all 40 trials covered" still tolerates a flip or two rather than none.
double StandardError(const std::string& column, std::int64_t count, double mean, double se) {
  if (IsRateColumn(column) && count > 0 && std::isfinite(mean)) {
    const double n = static_cast<double>(count);
    const double p = std::clamp(mean, 1.0 / n, 1.0 - 1.0 / n);
    return p > 0.0 && p < 1.0 ? std::sqrt(p * (1.0 - p) / n) : 0.0;
  }
  return std::isfinite(se) ? se : 0.0;
}

constexpr const char* kToleranceRule =
    "# tolerance: a number moved when |now - golden| > z sqrt(se_now^2 + se_golden^2) (z = 5 unless\n"
    "#   --z), se = its Monte Carlo standard error: sample std / sqrt(count) for a mean over trials;\n"
    "#   binomial sqrt(p (1 - p) / count), p kept >= 1/count from 0 and 1, for 0/1 columns (in_ci*,\n"
    "#   missing/, failed/, converged/, *found/); columns with se 0 (exact constants such as\n"
    "#   edf_exact) must match to 1e-12 relative. A changed trial count is always a move.\n";

}  // namespace

bool ReadGoldenTable(const std::string& path_text, GoldenTable* table, std::string* why) {
  const std::filesystem::path path(path_text);
  std::ifstream in(path);
  if (!in) {
    *why = "no golden table " + path.string() + " (create it with allanlab validate --update)";
    return false;
  }
  std::string line;
  int line_number = 0;
  bool header = false;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.empty() || line[0] == '#') continue;
    if (!header) {
      header = true;
      if (line != "point,column,count,mean,standard_error") {
        *why = path.string() + ":" + std::to_string(line_number) + ": unexpected header";
        return false;
      }
      continue;
    }
    std::istringstream fields(line);
    std::string point, column, count, mean, se;
    if (!std::getline(fields, point, ',') || !std::getline(fields, column, ',') ||
        !std::getline(fields, count, ',') || !std::getline(fields, mean, ',') ||
        !std::getline(fields, se, ',')) {
      *why = path.string() + ":" + std::to_string(line_number) + ": expected 5 fields";
      return false;
    }
    try {
      (*table)[{std::stoi(point), column}] = {std::stoll(count), std::stod(mean), std::stod(se)};
    } catch (const std::exception&) {
      *why = path.string() + ":" + std::to_string(line_number) + ": bad number";
      return false;
    }
  }
  return true;
}

bool WriteGoldenTable(const std::string& path, const SweepSpec& spec, const std::vector<PointStats>& stats,
                      const std::string& provenance_lines, std::string* why) {
  AtomicFile out;
  if (!out.Open(path, why)) return false;
  out.stream() << provenance_lines << "# spec: " << spec.name << " (hash "
               << std::hex << spec.Hash() << std::dec << ")\n"
               << kToleranceRule << "point,column,count,mean,standard_error\n";
  for (const PointStats& point : stats) {
    for (const ColumnStats& c : point.columns) {
      out.stream() << point.point << ',' << c.column << ',' << c.count << ',' << SignificantDigits(c.mean, 17) << ','
                   << SignificantDigits(c.standard_error, 17) << '\n';
    }
  }
  return out.Commit(why);
}

std::vector<std::string> CompareWithGolden(const std::string& name, const GoldenTable& golden,
                                           const std::vector<PointStats>& stats, double z,
                                           std::int64_t* compared) {
  std::vector<std::string> moved;
  GoldenTable seen;
  for (const PointStats& point : stats) {
    for (const ColumnStats& c : point.columns) {
      const auto key = std::make_pair(point.point, c.column);
      seen[key] = {};
      std::ostringstream where;
      where << name << " point " << point.point << ' ' << c.column;
      const auto it = golden.find(key);
      if (it == golden.end()) {
        moved.push_back(where.str() + ": new (not in the golden table)");
        continue;
      }
      ++*compared;
      const GoldenValue& g = it->second;
      const bool both_nan = std::isnan(g.mean) && std::isnan(c.mean);
      const double se_now = StandardError(c.column, c.count, c.mean, c.standard_error);
      const double se_old = StandardError(c.column, g.count, g.mean, g.standard_error);
      const double diff = c.mean - g.mean;
      const double tolerance = z * std::sqrt(se_now * se_now + se_old * se_old) +
                               1e-12 * std::max(std::abs(c.mean), std::abs(g.mean));
      if (g.count != c.count) {
        moved.push_back(where.str() + ": " + std::to_string(c.count) + " trials counted, golden " +
                        std::to_string(g.count));
      } else if (!both_nan && !(std::abs(diff) <= tolerance)) {
        const double sigma = std::sqrt(se_now * se_now + se_old * se_old);
        moved.push_back(where.str() + ": " + SignificantDigits(c.mean, 6) + " +- " + SignificantDigits(se_now, 6) + ", golden " +
                        SignificantDigits(g.mean, 6) + " +- " + SignificantDigits(se_old, 6) + " (" +
                        (sigma > 0 ? SignificantDigits(diff / sigma, 6) + " sigma" : std::string("exact value")) +
                        ")");
      }
    }
  }
  for (const auto& [key, value] : golden) {
    if (!seen.count(key)) {
      moved.push_back(name + " point " + std::to_string(key.first) + ' ' + key.second +
                      ": gone (in the golden table only)");
    }
  }
  return moved;
}

}  // namespace allanlab::experiments
