#include "estimators/estimate_quantile_table.h"

namespace allanlab::estimators {
namespace {

struct Entry {
  bool ok;
  double low, high;
};

constexpr std::int64_t kLengths = kTabulatedLongestRecord - kTabulatedShortestRecord + 1;

// kEntries[-alpha][length - kTabulatedShortestRecord], written by
// tests/tools/make_estimate_quantile_table.cc as hexadecimal floats (exact bits).
constexpr Entry kEntries[3][kLengths] = {
#include "estimators/estimate_quantile_table_entries.inc"
};

}  // namespace

std::optional<EstimateQuantiles> TabulatedEstimateQuantiles(Statistic s, int alpha, std::int64_t m,
                                                            std::int64_t n_rate, double confidence) {
  if (s != Statistic::kAllanOverlapping || confidence != kTabulatedConfidence ||
      m <= kReducedAveragingFactor || alpha < -2 || alpha > 0 || TermCount(s, m, n_rate) < 1) {
    return std::nullopt;
  }
  const std::int64_t length = ReducedRecordLength(m, n_rate);
  if (length < kTabulatedShortestRecord || length > kTabulatedLongestRecord) return std::nullopt;
  const Entry& e = kEntries[-alpha][length - kTabulatedShortestRecord];
  EstimateQuantiles q;
  q.ok = e.ok;
  if (e.ok) {
    q.low = e.low;
    q.high = e.high;
  }
  return q;
}

}  // namespace allanlab::estimators
