#pragma once
// The Allan-family statistics written out as NIST SP 1065 states them (cluster means of rate,
// the phase sums for MVAR, the explicit doubly reflected record for TOTVAR), in long double:
// obvious, and independent of estimators/ (no blocking, no SIMD, no shared passes), so the fast
// code can be checked against them. O(N) per tau, O(N m) for MVAR and TVAR.
#include <cstdint>
#include <span>

#include "estimators/statistic.h"

namespace allanlab::testing_support {

// The variance (rate units^2; angle units^2 for kTime) of `rate` (tau0 = tau0_s) at m, which
// must satisfy 1 <= m <= estimators::MaxAveragingFactor(s, rate.size()).
long double DirectStatistic(estimators::Statistic s, std::span<const double> rate, std::int64_t m,
                            double tau0_s = 1.0);

}  // namespace allanlab::testing_support
