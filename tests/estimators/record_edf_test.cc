// The record EDF as computed (vectorised difference terms, the widest lag-product kernel) against
// the straightforward computation of the same definition (terms formed one by one, lag products
// by the portable code), bit for bit: the EDF sets the printed intervals' last digits, so a
// faster path may not move them.
#include "estimators/record_edf.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <vector>

#include "estimators/lag_products.h"
#include "estimators/phase_integral.h"
#include "estimators/statistic.h"

namespace allanlab::estimators {
namespace {

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// RecordEdf as record_edf.h defines it, written out directly.
double StraightforwardRecordEdf(Statistic s, std::span<const double> phase, std::int64_t m, std::int64_t max_terms) {
  const auto n = static_cast<std::int64_t>(phase.size()) - 1;
  if (!RecordEdfAvailable(s, m, n, max_terms)) return 0.0;
  const int d = DifferenceOrder(s);
  const std::int64_t stride = IsOverlapping(s) ? 1 : m;
  const std::int64_t total = TermCount(s, m, n);
  const std::int64_t used = std::min(total, max_terms);
  const std::int64_t first = (total - used) / 2;
  std::vector<double> a;
  for (std::int64_t j = 0; j < used; ++j) {
    const double* x = phase.data() + (first + j) * stride;
    a.push_back(d == 2 ? (x[2 * m] - x[m]) - (x[m] - x[0]) : ((x[3 * m] - x[0]) - 3.0 * (x[2 * m] - x[m])));
  }
  const std::int64_t window = (d * m + stride - 1) / stride;
  const std::int64_t lags = std::min(window, total - 1);
  std::vector<double> products(static_cast<std::size_t>(lags + 1));
  LagProducts(a, products, LagKernel::kPortable);
  const double c0 = products[0] / static_cast<double>(used);
  if (!(c0 > 0.0)) return 0.0;
  const double big_m = static_cast<double>(total);
  double raw = 1.0;
  for (std::int64_t k = 1; k <= lags; ++k) {
    const double rho = products[static_cast<std::size_t>(k)] / static_cast<double>(used - k) / c0;
    raw += 2.0 * (1.0 - static_cast<double>(k) / big_m) * rho * rho;
  }
  const double sum = raw / (1.0 + 2.0 * static_cast<double>(window) / static_cast<double>(used));
  return big_m / std::max(sum, 1.0);
}

// White rate noise, a random walk over it, and a bias with an AR(1) term (flicker-like at short taus).
std::vector<std::vector<double>> Records(std::size_t n) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal;
  std::vector<std::vector<double>> records(3, std::vector<double>(n));
  double walk = 0.0, ar = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    records[0][i] = normal(rng);
    walk += 1e-2 * normal(rng);
    records[1][i] = 0.1 * normal(rng) + walk;
    ar = 0.99 * ar + 0.1 * normal(rng);
    records[2][i] = 3.0 + normal(rng) + ar;
  }
  return records;
}

TEST(RecordEdf, SameBitsAsTheStraightforwardComputation) {
  const std::vector<std::int64_t> grid = {1, 2, 3, 4, 5, 7, 8, 10, 13, 16, 20, 32, 50, 64, 100, 128};
  int compared = 0;
  for (const std::vector<double>& rate : Records(300000)) {
    std::vector<double> phase(rate.size() + 1);
    IntegrateAbout(rate, ReferenceLevel(rate), phase);
    for (Statistic s : {Statistic::kAllanOverlapping, Statistic::kAllanNonOverlapping,
                        Statistic::kHadamardOverlapping, Statistic::kHadamardNonOverlapping}) {
      // The default cap, a larger one, and caps that leave short last blocks of the lag products.
      for (std::int64_t max_terms : {kRecordEdfMaxTerms, std::int64_t{1} << 18, std::int64_t{40000}, std::int64_t{9000}}) {
        for (std::int64_t m : grid) {
          const double expected = StraightforwardRecordEdf(s, phase, m, max_terms);
          const double got = RecordEdf(s, phase, m, max_terms);
          EXPECT_TRUE(SameBits(expected, got))
              << "statistic " << static_cast<int>(s) << " m " << m << " max_terms " << max_terms << ": "
              << expected << " vs " << got;
          compared += expected > 0.0;
        }
      }
    }
  }
  EXPECT_GT(compared, 150);  // most of the grid has a record EDF
}

}  // namespace
}  // namespace allanlab::estimators
