// Writes estimators/estimate_quantile_table_entries.inc to stdout: ComputeEstimateQuantiles for
// the overlapping AVAR at the tabulated confidence, alpha 0, -1, -2, at every tabulated reduced
// record length, as hexadecimal floats so that the table holds the computed bits exactly.
// Run after any change to what the quantiles are computed from (estimate_distribution.cc):
//   build/tests/make_estimate_quantile_table > estimators/estimate_quantile_table_entries.inc
// tests/estimators/estimate_quantile_table_test.cc fails until the table is rewritten.
#include <cstdio>

#include "estimators/estimate_quantile_table.h"

int main() {
  using namespace allanlab::estimators;
  std::printf("// Written by tests/tools/make_estimate_quantile_table.cc; do not edit.\n");
  for (int alpha = 0; alpha >= -2; --alpha) {
    std::printf("{  // alpha %d\n", alpha);
    for (std::int64_t n = kTabulatedShortestRecord; n <= kTabulatedLongestRecord; ++n) {
      // m = 2 m' on 2 n samples reduces to exactly n samples at m'.
      const EstimateQuantiles q = ComputeEstimateQuantiles(
          Statistic::kAllanOverlapping, alpha, 2 * kReducedAveragingFactor, 2 * n, kTabulatedConfidence);
      std::printf("    {%s, %a, %a},  // %lld\n", q.ok ? "true" : "false", q.ok ? q.low : 0.0,
                  q.ok ? q.high : 0.0, static_cast<long long>(n));
    }
    std::printf("},\n");
  }
  return 0;
}
