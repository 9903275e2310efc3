#pragma once
// An IIR band-limit section (band_limit.h's Biquad, first- or second-order) advanced one output
// period at a time (docs/theory.md §2.9, §6.1). Over the L internal samples of a period, with the
// held input h constant and the internal white noise u_i independent, the section's state at the
// period's end (z1, z2 of the transposed direct form) and the period's output (its last internal
// sample, or the mean of its L) are linear in (state before, h) plus three jointly Gaussian sums
// of the u_i:
//   (z1', z2', out) = M (z1, z2) + v h + sum_i w_i u_i.
// Drawing those sums from their 3 x 3 covariance (factored to its rank: 1 or 2 for a first-order
// section, up to 3 for a second-order one) gives the output exactly in distribution with at most 3
// Gaussian draws per output sample instead of L: another random stream than the internal-rate
// recursion's, the same law. Without white noise (no draws) it is that recursion's linear map.
#include <array>

#include "sim/band_limit.h"

namespace allanlab::sim {

class SectionPeriod {
 public:
  // `section`: the chain's IIR design (its state is ignored: the period starts from zero state);
  // `internal_variance`: the variance of the white noise added at each internal sample (0: none);
  // `average`: the output is the period mean (else the last internal sample).
  SectionPeriod(const Biquad& section, int oversampling, double internal_variance, bool average);

  // Unit normal draws per output period (0 without white noise).
  int draws() const { return draws_; }
  // One output period with held input `held` and draws()'s unit normal deviates z; returns the
  // output sample.
  double Step(double held, const std::array<double, 3>& z);

 private:
  // Rows: z1 after, z2 after, output.
  std::array<std::array<double, 2>, 3> state_map_{};
  std::array<double, 3> held_map_{};
  std::array<std::array<double, 3>, 3> noise_factor_{};  // lower-triangular, columns beyond draws_ zero
  int draws_ = 0;
  bool first_order_ = false;  // b1 = b2 = a2 = 0: z2 stays 0, its row and column are skipped
  double z1_ = 0.0, z2_ = 0.0;
};

}  // namespace allanlab::sim
