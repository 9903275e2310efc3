// BandLimitChain::WhiteOutputAutocovariance (the IIR kinds' geometric tail in closed form)
// against its definition summed here term by term over the chain's response ge:
// R(j) = var * sum_n ge_n ge_{n+jL}, for every low-pass kind, both output samplings, oversamplings
// 1 to 8, and cutoffs from near the internal Nyquist frequency down to 0.15 Hz, where the response
// runs to ~4.5e4 internal samples. The direct sum stops where the response was truncated (1e-18 of
// its peak), the closed form does not, and the response's values carry the double-precision
// recursion's rounding, one unit of 2.2e-16 per step at most: they agree to len(ge) x 2.2e-16 (+
// 1e-14) of R(0) at every lag (seen: up to 1.0e-16 x len(ge); at 0.05 Hz, 1.4e5 taps, 1.35e-11).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "sim/band_limit.h"

namespace allanlab::sim {
namespace {

std::vector<long double> DirectSum(const BandLimitChain& chain, std::int64_t lags) {
  const std::vector<double>& g = chain.internal_response();
  const auto l = static_cast<std::size_t>(chain.oversampling());
  std::vector<long double> r(static_cast<std::size_t>(lags), 0.0L);
  for (std::size_t j = 0; j < r.size() && j * l < g.size(); ++j) {
    for (std::size_t n = 0; n + j * l < g.size(); ++n) r[j] += static_cast<long double>(g[n]) * g[n + j * l];
  }
  return r;
}

TEST(WhiteOutputAutocovarianceTest, MatchesTheDirectSum) {
  constexpr double kRate = 100.0;
  constexpr double kVariance = 2.5;
  int cases = 0;
  for (LowPassKind kind : {LowPassKind::kFirstOrder, LowPassKind::kFirstOrderBilinear, LowPassKind::kButterworth2,
                           LowPassKind::kButterworth2ImpulseInvariant, LowPassKind::kMovingAverage, LowPassKind::kCic2}) {
    for (int l : {1, 3, 8}) {
      for (OutputSampling sampling : {OutputSampling::kPoint, OutputSampling::kAverage}) {
        for (double fc : {0.15, 0.7, 9.0, 38.0, 0.4 * l * kRate}) {
          const BandLimit limit{kind, fc, l, sampling};
          std::string why;
          if (!limit.IsValid(kRate, &why)) continue;
          const BandLimitChain chain(limit, kRate);
          const std::int64_t lags =
              static_cast<std::int64_t>(chain.internal_response().size()) / l + 3;  // past the support
          const std::vector<double> r = chain.WhiteOutputAutocovariance(kVariance, lags);
          const std::vector<long double> direct = DirectSum(chain, lags);
          ASSERT_EQ(r.size(), direct.size());
          const double scale = kVariance * static_cast<double>(direct[0]);
          double worst = 0.0;
          for (std::size_t j = 0; j < r.size(); ++j) {
            worst = std::max(worst, std::abs(r[j] - kVariance * static_cast<double>(direct[j])) / scale);
          }
          const double bound = 2.2e-16 * static_cast<double>(chain.internal_response().size()) + 1e-14;
          EXPECT_LT(worst, bound) << LowPassKindName(kind) << " fc " << fc << " L " << l << " "
                                  << (sampling == OutputSampling::kAverage ? "average" : "point") << ", "
                                  << chain.internal_response().size() << " taps";
          ++cases;
        }
      }
    }
  }
  EXPECT_GE(cases, 120);
}

}  // namespace
}  // namespace allanlab::sim
