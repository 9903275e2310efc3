#pragma once
// The Allan family of two-sample statistics allanlab computes, and the facts about each that the
// confidence-interval and noise-identification code needs (difference order, overlap, modified).
#include <cstdint>
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

// Largest averaging factor m the estimator is computed for on n rate samples (n + 1 phase
// points): n/2 for AVAR and OAVAR; n/3 for MVAR, TVAR, HVAR and OHVAR; n - 1 for TOTVAR, whose
// doubly reflected extension (NIST SP 1065 §5.2.11) reaches every m below the record length.
std::int64_t MaxAveragingFactor(Statistic s, std::int64_t n);

// Number of squared differences averaged at averaging factor m on n rate samples, 0 when
// m < 1 or m > MaxAveragingFactor(s, n). With M = floor(n/m) clusters (NIST SP 1065 §5.2):
// AVAR M - 1, OAVAR n - 2m + 1, MVAR and TVAR n - 3m + 2 (= phase points - 3m + 1),
// HVAR M - 2, OHVAR n - 3m + 1, TOTVAR n - 1.
std::int64_t TermCount(Statistic s, std::int64_t m, std::int64_t n);

}  // namespace allanlab::estimators
