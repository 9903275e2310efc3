#pragma once
// Exact expectations of the Allan-family estimators of a rate record from its autocovariance,
// written here from the definitions (docs/theory.md §1.1, §1.2, §2.10; NIST SP 1065 §5.2 for the
// total variance's reflected extension), apart from the estimators and from sim/, so that the
// tables that judge the estimators do not take their reference from the code they judge.
//
// Every statistic is an average of squared linear filters of the record, so its expectation is
// sum_{i,j} c_i c_j r(|i - j|) with the filter's taps c (unit sample period; rate samples):
//   AVAR, OAVAR   c = (1/(m sqrt 2)) [-1 x m, +1 x m]
//   HVAR, OHVAR   c = (1/(m sqrt 6)) [+1 x m, -2 x m, +1 x m]
//   MVAR          the Allan filter summed over m consecutive starts, divided by m (3m - 1 taps)
//   TVAR          tau^2 MVAR / 3 with tau = m tau0 (angle units squared)
//   TOTVAR        the average over the n - 1 centres of the second difference of the phase
//                 extended by reflection at both ends (x*_{-k} = 2 x_0 - x_k,
//                 x*_{n+k} = 2 x_n - x_{n-k}); the centres from m to n - m are Allan differences,
//                 the others are folded filters, each expanded into its taps on the record.
// r(k), k >= 0, may be a generalised autocovariance (defined up to a constant, e.g. -k/2 for a
// random walk of unit steps): every filter above has taps summing to zero.
#include <cstdint>
#include <functional>

#include "estimators/statistic.h"

namespace allanlab::experiments {

using Autocovariance = std::function<double(std::int64_t)>;

// E[statistic(m)] on a record of n rate samples with sample period tau0 [s] (tau0 only scales
// TVAR). Throws std::invalid_argument for m < 1 or m beyond what the statistic reaches on n.
double FamilyExpectation(estimators::Statistic statistic, std::int64_t m, std::int64_t n,
                         double tau0_s, const Autocovariance& r);

}  // namespace allanlab::experiments
