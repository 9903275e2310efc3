#pragma once
// Exact mean and variance of any Allan-family estimate that averages squared linear differences
// of the rate samples, for Gaussian noise with a known (generalised) autocovariance R
// (docs/theory.md §3.1, Isserlis). The estimate is V_hat = (1/T) sum_{t<T} D_{t s}^2 with
// D_u = sum_i c_i y_{u+i} (c the statistic's rate filter, s the stride of the start indices), so
//   E[V_hat]   = r_D(0),
//   Var(V_hat) = (2 / T^2) sum_{|k|<T} (T - |k|) r_D(k s)^2,
//   r_D(l)     = Cov(D_u, D_{u+l}) = sum_{|j|<L} acf_c(j) R(|l + j|),  acf_c(j) = sum_i c_i c_{i+j}
// (= 2 tr((A Sigma)^2) for the quadratic form y'Ay = V_hat). A generalised R (random walk,
// stationary-increment flicker) is valid because every filter here sums to zero.
#include <cstdint>
#include <span>
#include <vector>

#include "estimators/exact_avar_variance.h"  // AvarMoments
#include "estimators/statistic.h"

namespace allanlab::estimators {

// Rate filter c of the statistic at averaging factor m >= 1, normalised so that E[D^2] is the
// statistic's expectation (units of c: 1, so D has the rate's units):
//   AVAR, OAVAR   (1/(m sqrt2)) [-1 x m, +1 x m]                     length 2m
//   HVAR, OHVAR   (1/(m sqrt6)) [+1 x m, -2 x m, +1 x m]             length 3m
//   MVAR          c_k = (1/(m^2 sqrt2)) sum_{j>k} e_j, e = [1 x m, -2 x m, 1 x m] the phase
//                 filter of NIST SP 1065 eq. (14) (box of m second differences)  length 3m - 1
// Empty for TOTVAR (its reflected extension is not a stationary filter) and TVAR.
std::vector<double> DifferenceFilter(Statistic s, std::int64_t m);

// Moments of (1/count) sum_{t<count} D_{t stride}^2 for the filter c (sum c = 0) and
// `autocovariance[j]`, j = 0 .. (count - 1) stride + len(c) - 1 (rate^2; generalised allowed).
// Long double inside: the random walk's R grows like j and the filter cancels it.
// Cost O(count len(c)). Precondition: count >= 1, stride >= 1, c non-empty.
AvarMoments ExactQuadraticMoments(std::span<const double> autocovariance,
                                  std::span<const double> filter, std::int64_t count,
                                  std::int64_t stride);

}  // namespace allanlab::estimators
