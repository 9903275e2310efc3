// The kept odd harmonic sums behind Kasdin flicker's autocovariance are the bits of summing afresh,
// however the kept vector was extended, and FillAutocovariance scales them as before.
#include <cstddef>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "sim/flicker_noise.h"

namespace allanlab::sim {
namespace {

std::vector<double> Fresh(std::size_t n) {
  std::vector<double> out(n);
  long double harmonic_odd = 0.0L;
  for (std::size_t k = 0; k < n; ++k) {
    if (k > 0) harmonic_odd += 1.0L / (2.0L * k - 1.0L);
    out[k] = static_cast<double>(harmonic_odd);
  }
  return out;
}

TEST(OddHarmonicSums, KeptValuesAreTheFreshBits) {
  const std::vector<double> fresh = Fresh(300000);
  for (std::size_t n : {1, 7, 1000, 999, 250000, 300000}) {  // extended in steps, then read back
    const auto kept = OddHarmonicSums(n);
    ASSERT_GE(kept->size(), n);
    for (std::size_t k = 0; k < n; ++k) ASSERT_EQ((*kept)[k], fresh[k]) << "n " << n << " k " << k;
  }
}

TEST(OddHarmonicSums, AutocovarianceIsTheScaledSum) {
  const FlickerNoise f{3.7e-6};
  std::vector<double> r(5000);
  f.FillAutocovariance(0.01, r);
  const std::vector<double> fresh = Fresh(r.size());
  const double scale = 2.0 * f.bias_instability_rad_per_s * f.bias_instability_rad_per_s / std::numbers::pi;
  for (std::size_t k = 0; k < r.size(); ++k) ASSERT_EQ(r[k], -scale * fresh[k]) << k;
}

// Beyond the kept length the sums are not kept, and the autocovariance is summed in place alike.
TEST(OddHarmonicSums, LongerThanKeptIsSummedInPlace) {
  const std::size_t n = (std::size_t{1} << 22) + 3;
  EXPECT_EQ(OddHarmonicSums(n), nullptr);
  const FlickerNoise f{1.1e-5};
  std::vector<double> r(n);
  f.FillAutocovariance(0.01, r);
  const std::vector<double> fresh = Fresh(n);
  const double scale = 2.0 * f.bias_instability_rad_per_s * f.bias_instability_rad_per_s / std::numbers::pi;
  for (std::size_t k = 0; k < n; k += 997) ASSERT_EQ(r[k], -scale * fresh[k]) << k;
  ASSERT_EQ(r[n - 1], -scale * fresh[n - 1]);
}

}  // namespace
}  // namespace allanlab::sim
