// Lag products of a series: against sums in long double, and the vector and portable code
// against each other bit for bit (the record EDF must not depend on the CPU).
#include "estimators/lag_products.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

namespace allanlab::estimators {
namespace {

std::vector<double> Series(std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.3, 1.0);
  std::vector<double> a(n);
  for (double& v : a) v = normal(rng);
  return a;
}

// Lengths around the block size and its multiples, lag counts not a multiple of four.
TEST(LagProductsTest, MatchLongDoubleSums) {
  for (std::size_t n : {std::size_t{9}, std::size_t{4099}, std::size_t{3 * 4096 + 2}, std::size_t{40000}}) {
    const std::vector<double> a = Series(n, static_cast<unsigned>(n));
    const std::size_t lags = std::min<std::size_t>(n, 11);
    std::vector<double> out(lags);
    LagProducts(a, out);
    for (std::size_t k = 0; k < lags; ++k) {
      long double exact = 0, magnitude = 0;
      for (std::size_t j = 0; j + k < n; ++j) {
        exact += static_cast<long double>(a[j]) * a[j + k];
        magnitude += std::fabs(static_cast<long double>(a[j]) * a[j + k]);
      }
      // Partial sums of at most 512 products each: rounding below 600 eps of the magnitude.
      EXPECT_NEAR(out[k], static_cast<double>(exact), 600 * 2.2e-16 * static_cast<double>(magnitude))
          << "n " << n << " lag " << k;
    }
  }
}

// Every kernel this CPU runs against the portable code: lengths that leave a short last block,
// lag counts that leave groups of every size (1 .. 8 lags), series shorter than a block.
TEST(LagProductsTest, EveryKernelGivesThePortableBitsBitForBit) {
  for (std::size_t n : {std::size_t{37}, std::size_t{4096 + 3}, std::size_t{5 * 4096 + 7}, std::size_t{1 << 18}}) {
    const std::vector<double> a = Series(n, 3);
    for (std::size_t lags : {std::size_t{1}, std::size_t{3}, std::size_t{5}, std::size_t{9}, std::size_t{17},
                             std::size_t{30}, std::size_t{257}}) {
      if (lags > n) continue;
      std::vector<double> portable(lags);
      LagProducts(a, portable, LagKernel::kPortable);
      for (LagKernel kernel : {LagKernel::kBest, LagKernel::kAvx512, LagKernel::kAvx2}) {
        if (!LagKernelRuns(kernel)) continue;
        std::vector<double> vector(lags);
        LagProducts(a, vector, kernel);
        EXPECT_EQ(std::memcmp(vector.data(), portable.data(), lags * sizeof(double)), 0)
            << "n " << n << " lags " << lags << " kernel " << static_cast<int>(kernel);
      }
    }
  }
}

}  // namespace
}  // namespace allanlab::estimators
