#pragma once
// How the band-limit chain (band_limit.h) changes a noise term's expected Allan variance, in
// O(len(q)) per averaging factor whatever the cutoff: SensorModel::ExpectedAvar's route for white
// and held stationary terms, and what lets fits re-evaluate a model at many cutoffs
// (estimators/fit/parametric_fit.h).
//
// Why it is cheap: the Allan kernel a(j) (docs/theory.md §1.2) is piecewise linear with kinks at lags
// 0, +-m, +-2m only; exactly,
//   a(j) = -3|j| + 2|j - m| + 2|j + m| - |j - 2m|/2 - |j + 2m|/2.
// A held term reaches the output through q (the held response), so its output autocovariance is
// R_y = rq * R_x with rq the even, unit-sum autocorrelation of q; then
// AVAR_y(m) = (1/(2m^2)) sum_j (a * rq)(j) R_x(j), and a * rq differs from a only within
// len(q) lags of the kinks, because a symmetric unit-sum kernel leaves linear pieces unchanged:
//   (a * rq)(j) - a(j) = -3 phi(j) + 2 phi(j - m) + 2 phi(j + m) - phi(j - 2m)/2 - phi(j + 2m)/2,
//   phi(x) = sum_d rq(d) |x + d| - |x|   (even, zero for |x| >= len(q) - 1).
// So the change of the AVAR is O(len(q)) per m for any m, from R_x at three short lag windows:
//   dAVAR(m) = (1/(2m^2)) sum_|x|<len(q) phi(x) [-3 R_x(|x|) + 4 R_x(|m + x|) - R_x(|2m + x|)].
// White rate noise enters at the internal rate (wideband path); its output autocovariance is
// zero beyond the chain's response, so its filtered AVAR is a sum over that short support.
// Both are exact to rounding (the direct quadratic form over the chain's output autocovariance,
// regrouped), for every m (docs/theory.md §2.9).
#include <cstdint>
#include <span>
#include <vector>

#include "sim/avar_theory.h"
#include "sim/band_limit.h"
#include "sim/noise_term.h"

namespace allanlab::sim {

// Change of a term's expected AVAR (rad/s)^2 when the chain is inserted, at each m of `ms`:
// filtered minus the term's own ExpectedAvar(m, tau0_s, shape). Returns false (change untouched)
// for terms with no fast form (harmonic, exponential drift, bias step), true for every other term:
// SensorModel::ExpectedAvar relies on that. Zero for digital terms (after the filter) and the rate
// ramp (filter-invariant). Exact for white rate noise and held terms with a stationary
// (generalised) autocovariance: random walk, Gauss-Markov, telegraph, Gauss-Markov-sum flicker.
// Kasdin flicker: the change is that of its stationary-increment form, while its own exact AVAR
// and the exact chain path start it from a zero state at the first sample; the difference is
// a start-up effect shared by the T = N - 2m + 1 Allan differences, below 0.5 (tc + 1)/T of the
// flicker AVAR (tc = fs/(2 pi fc) samples; tests/sim/band_limited_avar_test.cc), far below the
// estimation noise of any tau (whose relative size is at least ~1/sqrt(T)).
// Precondition: every m in [1, N/2] of the record the caller's own AVARs refer to.
bool BandLimitAvarChange(const NoiseTerm& term, const BandLimitChain& chain, double tau0_s,
                         std::span<const std::int64_t> ms, std::vector<double>* change);

}  // namespace allanlab::sim
