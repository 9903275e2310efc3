#pragma once
// The Allan family of two-sample statistics allanlab computes, and the facts about each that the
// confidence-interval and noise-identification code needs (difference order, overlap, modified).
#include <string_view>

namespace allanlab::estimators {

enum class Statistic {
  kAllanNonOverlapping,     // AVAR, IEEE 952 Annex C / seed paper eq. (2)
  kAllanOverlapping,        // OAVAR, IEEE 1554's recommendation
  kModifiedAllan,           // MVAR (always overlapping)
  kHadamardNonOverlapping,  // HVAR
  kHadamardOverlapping,     // OHVAR (drift-insensitive)
  kTotal,                   // TOTVAR (doubly reflected extension, NIST SP 1065)
  kTime,                    // TVAR = tau^2 MVAR / 3 (time deviation squared; angle^2 for gyros)
};

// Stable ids used on the command line and in JSON: "nonoverlapping", "overlapping", "modified",
// "hadamard_nonoverlapping", "hadamard", "total", "time".
std::string_view StatisticId(Statistic s);
bool ParseStatistic(std::string_view id, Statistic* s);

// Difference order d of the statistic's filter (Greenhall & Riley 2003): 2 for the Allan and
// modified Allan family, 3 for Hadamard. (Phase differences: d = 2 is the Allan second difference.)
int DifferenceOrder(Statistic s);
bool IsOverlapping(Statistic s);
bool IsModified(Statistic s);  // MVAR and TVAR

}  // namespace allanlab::estimators
