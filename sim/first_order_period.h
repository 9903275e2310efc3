#pragma once
// The one-pole (impulse-invariant first-order) band-limit advanced one output period at a time
// (docs/theory.md §2.9). Over the L internal samples of a period, with the held input h constant and
// the internal white noise u_i independent, the filter state at the period's end and the period's
// mean are linear in (state before, h) plus a pair of jointly Gaussian sums of the u_i:
//   end  = p^L y + h b0 sum_{j<L} p^j                 + E1,  E1 = b0 sum_i p^(L-1-i) u_i
//   mean = (1/L) sum_i (p^(i+1) y + h b0 sum_{d<=i} p^d) + E2,  E2 = (b0/L) sum_i (sum_{d<L-i} p^d) u_i
// Drawing (E1, E2) from their 2 x 2 covariance gives the output exactly in distribution with 2
// Gaussian draws per output sample (1 when point-sampled) instead of L: another random stream than
// the internal-rate recursion's, the same law.
#include "sim/band_limit.h"

namespace allanlab::sim {

class FirstOrderPeriod {
 public:
  // `design`: the one-pole section (b1 = b2 = a2 = 0); `internal_variance`: the variance of the
  // white noise added at each internal sample (0: none); `average`: the output is the period mean
  // (else the last internal sample).
  FirstOrderPeriod(const Biquad& design, int oversampling, double internal_variance, bool average);

  // Draws per output period (0 without white noise, 1 point-sampled, 2 averaged).
  int draws() const { return draws_; }
  // One output period with held input `held` and unit normal draws z1 (and z2 when averaged);
  // returns the output sample.
  double Step(double held, double z1, double z2) {
    const double e1 = c11_ * z1;
    if (!average_) return y_ = p_l_ * y_ + held_to_end_ * held + e1;
    const double mean = state_to_mean_ * y_ + held_to_mean_ * held + (c21_ * z1 + c22_ * z2);
    y_ = p_l_ * y_ + held_to_end_ * held + e1;
    return mean;
  }

 private:
  bool average_;
  int draws_ = 0;
  double p_l_ = 0.0, held_to_end_ = 0.0, state_to_mean_ = 0.0, held_to_mean_ = 0.0;
  double c11_ = 0.0, c21_ = 0.0, c22_ = 0.0;  // Cholesky factor of Cov(E1, E2)
  double y_ = 0.0;                            // filter state after the last internal sample
};

}  // namespace allanlab::sim
