#include "estimators/statistic.h"

namespace allanlab::estimators {
namespace {

struct StatisticFacts {
  Statistic statistic;
  std::string_view id;
  int difference_order;
  bool overlapping;
  bool modified;
};

// One row per statistic keeps the id, the parser and the facts from drifting apart.
constexpr StatisticFacts kFacts[] = {
    {Statistic::kAllanNonOverlapping, "nonoverlapping", 2, false, false},
    {Statistic::kAllanOverlapping, "overlapping", 2, true, false},
    {Statistic::kModifiedAllan, "modified", 2, true, true},
    {Statistic::kHadamardNonOverlapping, "hadamard_nonoverlapping", 3, false, false},
    {Statistic::kHadamardOverlapping, "hadamard", 3, true, false},
    // Greenhall & Riley treat TOTVAR as an overlapping second difference; its EDF comes from
    // SP 1065 Table 7 instead, but the facts still describe the filter.
    {Statistic::kTotal, "total", 2, true, false},
    {Statistic::kTime, "time", 2, true, true},
};

const StatisticFacts& FactsOf(Statistic s) {
  for (const StatisticFacts& f : kFacts) {
    if (f.statistic == s) return f;
  }
  return kFacts[1];  // unreachable for valid enumerators
}

}  // namespace

std::string_view StatisticId(Statistic s) {
  for (const StatisticFacts& f : kFacts) {
    if (f.statistic == s) return f.id;
  }
  return {};
}

bool ParseStatistic(std::string_view id, Statistic* s) {
  for (const StatisticFacts& f : kFacts) {
    if (f.id == id) {
      *s = f.statistic;
      return true;
    }
  }
  return false;
}

int DifferenceOrder(Statistic s) { return FactsOf(s).difference_order; }
bool IsOverlapping(Statistic s) { return FactsOf(s).overlapping; }
bool IsModified(Statistic s) { return FactsOf(s).modified; }

std::int64_t MaxAveragingFactor(Statistic s, std::int64_t n) {
  if (n < 2) return 0;
  switch (s) {
    case Statistic::kAllanNonOverlapping:
    case Statistic::kAllanOverlapping:
      return n / 2;
    case Statistic::kModifiedAllan:
    case Statistic::kTime:
    case Statistic::kHadamardNonOverlapping:
    case Statistic::kHadamardOverlapping:
      return n / 3;
    case Statistic::kTotal:
      return n - 1;
  }
  return 0;
}

std::int64_t TermCount(Statistic s, std::int64_t m, std::int64_t n) {
  if (m < 1 || m > MaxAveragingFactor(s, n)) return 0;
  switch (s) {
    case Statistic::kAllanNonOverlapping:
      return n / m - 1;
    case Statistic::kAllanOverlapping:
      return n - 2 * m + 1;
    case Statistic::kModifiedAllan:
    case Statistic::kTime:
      return n - 3 * m + 2;
    case Statistic::kHadamardNonOverlapping:
      return n / m - 2;
    case Statistic::kHadamardOverlapping:
      return n - 3 * m + 1;
    case Statistic::kTotal:
      return n - 1;
  }
  return 0;
}

}  // namespace allanlab::estimators
