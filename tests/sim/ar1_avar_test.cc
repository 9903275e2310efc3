// Ar1Avar (closed form where m(1 - phi) >= 0.01, lag sum below) against the definition: the
// variance of adjacent block means from the AR(1) autocovariance, summed directly.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "sim/gauss_markov.h"

namespace allanlab::sim {
namespace {

// AVAR(m) = Var(block mean) - Cov(adjacent block means), autocovariance phi^|k|.
double Direct(std::int64_t m, double phi) {
  long double var = 0.0L, cov = 0.0L;
  for (std::int64_t i = 0; i < m; ++i) {
    for (std::int64_t j = 0; j < m; ++j) {
      var += std::pow(static_cast<long double>(phi), std::abs(i - j));
      cov += std::pow(static_cast<long double>(phi), m + j - i);
    }
  }
  return static_cast<double>((var - cov) / (static_cast<long double>(m) * m));
}

TEST(Ar1AvarTest, MatchesTheDefinitionAcrossTheClosedFormThreshold) {
  for (std::int64_t m : {1, 2, 5, 40, 300}) {
    for (double q : {1e-6, 1e-4, 3e-3, 0.05, 0.5, 0.9}) {
      const double expected = Direct(m, 1.0 - q);
      EXPECT_NEAR(Ar1Avar(m, 1.0 - q, 2.5) / (2.5 * expected), 1.0, 1e-9) << "m " << m << " q " << q;
    }
  }
}

}  // namespace
}  // namespace allanlab::sim
