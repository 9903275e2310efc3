// The record-length autocovariance fills that stop evaluating once the value can no longer
// change: an AR(1)'s generalised autocovariance v expm1(k ln phi) once expm1 is -1 exactly
// (FillAr1Autocovariance), and a resonance's once its envelope has underflowed to 0
// (Resonance::FillAutocovariance). The AR(1) fill must give the bits of expm1 at every lag, across
// the point where it stops calling it; the resonance's must agree with its geometric form
// Re[w z^k] (another formula, sim/resonance.h) at every lag, the zeros included.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <complex>
#include <cstdint>
#include <vector>

#include "sim/gauss_markov.h"
#include "sim/resonance.h"

namespace allanlab::sim {
namespace {

TEST(AutocovarianceSaturation, Ar1FillGivesExpm1sBitsAcrossItsStop) {
  constexpr double kVariance = 2.5e-9;
  for (double phi : {0.8, 0.95, 0.999}) {
    // ln phi from -0.22 to -0.001: the fill stops at lag 40 / |ln phi| (180 to 40000).
    const auto lags = static_cast<std::size_t>(80.0 / -std::log(phi)) + 10;
    for (std::int64_t first_lag : {std::int64_t{0}, std::int64_t{7}}) {
      std::vector<double> r(lags);
      FillAr1Autocovariance(phi, kVariance, r, first_lag);
      const double log_phi = std::log(phi);
      for (std::size_t j = 0; j < lags; ++j) {
        const double direct =
            kVariance * std::expm1(static_cast<double>(first_lag + static_cast<std::int64_t>(j)) * log_phi);
        ASSERT_EQ(r[j], direct) << "phi " << phi << " first lag " << first_lag << " lag " << j;
      }
    }
  }
}

TEST(AutocovarianceSaturation, ResonanceFillAgreesWithItsGeometricFormPastTheUnderflow) {
  constexpr double kTau0 = 0.01;
  const Resonance resonance{.sigma_rad_per_s = 6e-3, .frequency_hz = 20.5, .damping = 0.0225};
  const Resonance::GeometricForm g = resonance.Geometric(kTau0);
  const double var = resonance.sigma_rad_per_s * resonance.sigma_rad_per_s;
  // The envelope e^{-zeta w0 t} underflows near t = 745 / (zeta w0) = 257 s: 25700 lags.
  const std::size_t lags = 40000;
  std::vector<double> r(lags);
  resonance.FillAutocovariance(kTau0, r);
  // Each form evaluates e^{k L} (L = g.log_pole, a = -Re L > 0) from k L rounded to double, which
  // moves the value by up to eps k |L| of its size |w| e^{-k a}, plus a few roundings of its own
  // (exp, cos/sin, the weight): at most eps |w| (8 + k |L| e^{-k a}) each, and k |L| e^{-k a} peaks
  // at |L| / (a e). Two forms: twice that. (Seen: the largest difference is 0.29 of it.)
  constexpr double kEps = 2.220446049250313e-16;
  const double a = -g.log_pole.real();
  const double bound = 2.0 * kEps * std::abs(g.weight) * (8.0 + std::abs(g.log_pole) / (a * std::exp(1.0)));
  int zeros = 0;
  double largest = 0.0;
  for (std::size_t k = 0; k < lags; ++k) {
    const double geometric = std::real(g.weight * std::exp(static_cast<double>(k) * g.log_pole));
    ASSERT_NEAR(r[k], geometric, bound) << "lag " << k << " (bound " << bound / var << " of the variance)";
    largest = std::max(largest, std::abs(r[k] - geometric));
    zeros += r[k] == 0.0 ? 1 : 0;
  }
  std::printf("largest difference %.3g of the bound (%.3g of the variance)\n", largest / bound, bound / var);
  EXPECT_GT(zeros, 10000);  // the stop is reached within the fill
}

}  // namespace
}  // namespace allanlab::sim
