#include "sim/first_order_period.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace allanlab::sim {

FirstOrderPeriod::FirstOrderPeriod(const Biquad& design, int oversampling, double internal_variance, bool average)
    : average_(average) {
  const int l = oversampling;
  const long double p = -static_cast<long double>(design.a1), b0 = design.b0;
  // powers[i] = p^i, i = 0..L; partial[i] = sum_{d<=i} p^d.
  std::vector<long double> powers(l + 1), partial(l);
  powers[0] = 1.0L;
  for (int i = 1; i <= l; ++i) powers[i] = powers[i - 1] * p;
  long double acc = 0.0L;
  for (int i = 0; i < l; ++i) partial[i] = acc += powers[i];
  long double state_to_mean = 0.0L, held_to_mean = 0.0L;
  for (int i = 0; i < l; ++i) {
    state_to_mean += powers[i + 1];
    held_to_mean += b0 * partial[i];
  }
  p_l_ = static_cast<double>(powers[l]);
  held_to_end_ = static_cast<double>(b0 * partial[l - 1]);
  state_to_mean_ = static_cast<double>(state_to_mean / l);
  held_to_mean_ = static_cast<double>(held_to_mean / l);
  // Weights of u_i in E1 and E2, and their covariance.
  long double s11 = 0.0L, s12 = 0.0L, s22 = 0.0L;
  for (int i = 0; i < l; ++i) {
    const long double e1 = b0 * powers[l - 1 - i];
    const long double e2 = b0 * partial[l - 1 - i] / l;
    s11 += e1 * e1;
    s12 += e1 * e2;
    s22 += e2 * e2;
  }
  if (!(internal_variance > 0.0)) return;
  s11 *= internal_variance;
  s12 *= internal_variance;
  s22 *= internal_variance;
  const long double c11 = std::sqrt(s11);
  const long double c21 = c11 > 0.0L ? s12 / c11 : 0.0L;
  c11_ = static_cast<double>(c11);
  c21_ = static_cast<double>(c21);
  c22_ = static_cast<double>(std::sqrt(std::max(0.0L, s22 - c21 * c21)));
  draws_ = average_ ? 2 : 1;
}

}  // namespace allanlab::sim
