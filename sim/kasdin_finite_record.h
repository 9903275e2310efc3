#pragma once
// Exact expected overlapping Allan variance of Kasdin flicker (alpha = 1) generated from a zero
// state over a finite record (docs/theory.md §2.5.3), in O(log N) work per averaging
// factor instead of the O(N) direct sum of FiniteRecordAvar (avar_theory.h).
//
// With S(v) = sum_{k<=v} h_k the running sum of the Kasdin coefficients, g_e = (S(e) - 2 S(e-m) +
// S(e-2m)) / m and n_e the number of overlapping Allan differences that end at or after e,
//   E[OAVAR(m)] = (B^2 / (2 T)) sum_{e=0}^{N-1} n_e g_e^2,   T = N - 2m + 1,
// n_e = T for e < 2m and N - e beyond. The sum splits at e = m and e = 2m into three pieces on
// each of which the summand is an analytic function of e (S has the closed form
// S(v) = 2 Gamma(v + 3/2) / (sqrt(pi) Gamma(v + 1)), singular only at v <= -3/2). Each piece is
// summed exactly over its first 128 points (where the newly switched-on S(e - j m) varies fast);
// the rest is the integral of the analytic summand (12-point Gauss-Legendre on panels that double
// in length away from the singularity: Bernstein-ellipse error < 1e-18 relative) plus Gregory's
// end corrections up to eighth differences (error ~ 8! / 128^8 < 1e-12 of one end term, i.e.
// < 1e-14 of the sum). S itself comes from the asymptotic series of ln Gamma(z + 1/2) -
// ln Gamma(z) (z >= 129: truncation < 1e-19) or from the recursion h_k = h_{k-1} (k - 1/2) / k.
// Against the direct sum: agreement to ~1e-13 relative (tests/sim/kasdin_finite_record_test.cc).
#include <cstdint>

namespace allanlab::sim {

// E[OAVAR(m)] / B^2 for a record of n samples. Precondition: 1 <= m, 2m <= n.
// Memoised per (m, n): fits evaluate a flicker term's AVAR at the same curve for every B they try
// (it is B^2 times this), so each value is computed once and then read back, the same bits.
double KasdinOverlappingAvar(std::int64_t m, std::int64_t n);
// The same computed afresh (no memo).
double KasdinOverlappingAvarUncached(std::int64_t m, std::int64_t n);

// S(v) = sum_{k=0}^{v} h_k, h_0 = 1, h_k = h_{k-1} (k - 1/2) / k, continued analytically to real
// v >= 0 by 2 Gamma(v + 3/2) / (sqrt(pi) Gamma(v + 1)); S(v) = 0 for v < 0 (the zero state).
double KasdinCumulative(double v);

}  // namespace allanlab::sim
