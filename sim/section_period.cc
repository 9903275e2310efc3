#include "sim/section_period.h"

#include <cmath>
#include <vector>

namespace allanlab::sim {

SectionPeriod::SectionPeriod(const Biquad& s, int oversampling, double internal_variance, bool average) {
  const int l = oversampling;
  first_order_ = s.b1 == 0.0 && s.b2 == 0.0 && s.a2 == 0.0;
  // Each quantity as a linear combination of (z1 before, z2 before, h, u_0 .. u_{L-1}), run through
  // the section's own recursion (Biquad::Step) symbolically.
  const std::size_t width = 3 + static_cast<std::size_t>(l);
  using Form = std::vector<long double>;
  Form z1(width, 0.0L), z2(width, 0.0L), out(width, 0.0L), y(width, 0.0L);
  z1[0] = 1.0L;
  z2[1] = 1.0L;
  for (int i = 0; i < l; ++i) {
    Form x(width, 0.0L);
    x[2] = 1.0L;
    x[3 + static_cast<std::size_t>(i)] = 1.0L;
    for (std::size_t c = 0; c < width; ++c) y[c] = s.b0 * x[c] + z1[c];
    for (std::size_t c = 0; c < width; ++c) {
      const long double next_z1 = s.b1 * x[c] - s.a1 * y[c] + z2[c];
      z2[c] = s.b2 * x[c] - s.a2 * y[c];
      z1[c] = next_z1;
    }
    for (std::size_t c = 0; c < width; ++c) out[c] = average ? out[c] + y[c] / l : y[c];
  }
  const Form* rows[3] = {&z1, &z2, &out};
  for (int r = 0; r < 3; ++r) {
    state_map_[r] = {static_cast<double>((*rows[r])[0]), static_cast<double>((*rows[r])[1])};
    held_map_[r] = static_cast<double>((*rows[r])[2]);
  }
  if (!(internal_variance > 0.0)) return;
  long double cov[3][3] = {};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      for (std::size_t i = 3; i < width; ++i) cov[r][c] += (*rows[r])[i] * (*rows[c])[i];
      cov[r][c] *= internal_variance;
    }
  }
  // Cholesky to the covariance's rank: a pivot at rounding level (a first-order section's z2 is
  // always 0; point-sampled, its end state is a multiple of its output) adds no draw.
  const long double scale = cov[0][0] + cov[1][1] + cov[2][2];
  long double f[3][3] = {};
  for (int r = 0; r < 3; ++r) {
    long double pivot = cov[r][r];
    for (int k = 0; k < draws_; ++k) pivot -= f[r][k] * f[r][k];
    // Dependent on the rows before: its entries on their draws (set with those pivots) are all.
    if (!(pivot > 1e-13L * scale)) continue;
    const int d = draws_++;
    f[r][d] = std::sqrt(pivot);
    for (int q = r + 1; q < 3; ++q) {
      long double v = cov[q][r];
      for (int k = 0; k < d; ++k) v -= f[q][k] * f[r][k];
      f[q][d] = v / f[r][d];
    }
  }
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) noise_factor_[r][k] = static_cast<double>(f[r][k]);
  }
}

double SectionPeriod::Step(double held, const std::array<double, 3>& z) {
  if (first_order_) {
    // The general step's arithmetic without its zero terms (the same bits, a third of the work).
    double end = state_map_[0][0] * z1_ + held_map_[0] * held;
    double out = state_map_[2][0] * z1_ + held_map_[2] * held;
    for (int k = 0; k < draws_; ++k) {
      end += noise_factor_[0][k] * z[k];
      out += noise_factor_[2][k] * z[k];
    }
    z1_ = end;
    return out;
  }
  double next[3];
  for (int r = 0; r < 3; ++r) {
    double v = state_map_[r][0] * z1_ + state_map_[r][1] * z2_ + held_map_[r] * held;
    for (int k = 0; k < draws_; ++k) v += noise_factor_[r][k] * z[k];
    next[r] = v;
  }
  z1_ = next[0];
  z2_ = next[1];
  return next[2];
}

}  // namespace allanlab::sim
