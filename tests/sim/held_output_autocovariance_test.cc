// BandLimitChain::HeldOutputAutocovariance (double sums over the held autocorrelation, blocked so
// that they vectorise) against its definition summed here in long double over both taps of the
// held response q: R_y(j) = sum_a sum_b q_a q_b R_x(j + a - b), R_x even. Inputs: a flicker's
// generalised autocovariance (slowly varying, large at long lags), a random walk's (-|k|, which a
// unit-gain even filter leaves unchanged beyond its support) and a first-order Gauss-Markov one;
// lags from 0 across the reflected edge and about each block boundary. The double sum rounds
// twice per tap (a pair's sum and the running sum), each at most 2.2e-16 of a term no larger than
// the largest input the lag reads (rq sums to 1): the bound is len(rq) x 4.4e-16 of that input
// (seen: at most 0.26 of it, at 3 taps; 0.01-0.05 at 21-462 taps).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include "sim/band_limit.h"

namespace allanlab::sim {
namespace {

long double DirectHeld(const BandLimitChain& chain, const std::vector<double>& r_in, std::int64_t j) {
  const std::vector<double>& q = chain.held_response();
  const auto taps = static_cast<std::int64_t>(q.size());
  long double r = 0.0L;
  for (std::int64_t a = 0; a < taps; ++a) {
    for (std::int64_t b = 0; b < taps; ++b) {
      r += static_cast<long double>(q[a]) * q[b] * r_in[static_cast<std::size_t>(std::llabs(j + a - b))];
    }
  }
  return r;
}

// Every lag up to twice the support, the lags about each block boundary, and the last ones.
std::vector<std::int64_t> CheckedLags(std::int64_t taps, std::int64_t lags) {
  std::vector<std::int64_t> js;
  for (std::int64_t j = 0; j < std::min(lags, 2 * taps + 2); ++j) js.push_back(j);
  for (std::int64_t boundary = taps; boundary < lags; boundary += 2048) {
    for (std::int64_t j = std::max<std::int64_t>(0, boundary - 2); j < std::min(lags, boundary + 3); ++j) js.push_back(j);
  }
  for (std::int64_t j = lags - 3; j < lags; ++j) js.push_back(j);
  return js;
}

TEST(HeldOutputAutocovarianceTest, MatchesTheDoubleSumOverTheHeldResponse) {
  constexpr double kRate = 100.0;
  constexpr std::int64_t kLags = 5000;  // past the reflected edge and two 2048-lag blocks
  const std::vector<std::function<double(std::int64_t)>> inputs = {
      [](std::int64_t k) {  // Kasdin flicker's -(2/pi) sum_{i<=k} 1/(2i-1), up to its scale
        double h = 0.0;
        for (std::int64_t i = 1; i <= k; ++i) h += 1.0 / (2.0 * static_cast<double>(i) - 1.0);
        return -2.0 / M_PI * h;
      },
      [](std::int64_t k) { return -0.5 * static_cast<double>(k); },                 // random walk
      [](std::int64_t k) { return 3.0 * std::exp(-static_cast<double>(k) / 40.0); }  // Gauss-Markov
  };
  int cases = 0;
  for (LowPassKind kind : {LowPassKind::kFirstOrder, LowPassKind::kButterworth2, LowPassKind::kMovingAverage}) {
    for (double fc : {2.0, 38.0}) {
      const BandLimit limit{kind, fc, 8, OutputSampling::kAverage};
      std::string why;
      if (!limit.IsValid(kRate, &why)) continue;
      const BandLimitChain chain(limit, kRate);
      const std::size_t taps = chain.held_autocorrelation().size();
      for (const auto& input : inputs) {
        std::vector<double> r_in(static_cast<std::size_t>(kLags) + chain.held_response().size());
        for (std::size_t k = 0; k < r_in.size(); ++k) r_in[k] = input(static_cast<std::int64_t>(k));
        const std::vector<double> fast = chain.HeldOutputAutocovariance(r_in, kLags);
        ASSERT_EQ(fast.size(), static_cast<std::size_t>(kLags));
        double worst = 0.0;
        for (std::int64_t j : CheckedLags(static_cast<std::int64_t>(taps), kLags)) {
          double largest = 0.0;
          for (std::int64_t d = -static_cast<std::int64_t>(taps) + 1; d < static_cast<std::int64_t>(taps); ++d) {
            largest = std::max(largest, std::abs(r_in[static_cast<std::size_t>(std::llabs(j + d))]));
          }
          const double error = std::abs(fast[static_cast<std::size_t>(j)] - static_cast<double>(DirectHeld(chain, r_in, j)));
          worst = std::max(worst, error / (static_cast<double>(taps) * 4.4e-16 * largest));
        }
        EXPECT_LT(worst, 1.0) << LowPassKindName(kind) << " fc " << fc << ", " << taps << " taps";
        ++cases;
      }
    }
  }
  EXPECT_GE(cases, 12);
}

}  // namespace
}  // namespace allanlab::sim
