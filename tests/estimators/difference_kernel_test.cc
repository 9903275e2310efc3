// The fast passes behind the statistic values: every kernel version on this CPU, the chain and
// single-lag loops, the fused integration, and the bit-for-bit promises their headers make.
#include "estimators/difference_kernel.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "estimators/allan_family.h"
#include "estimators/difference_sums.h"
#include "estimators/phase_integral.h"

namespace allanlab::estimators {
namespace {

std::vector<double> Record(std::int64_t n, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  std::normal_distribution<double> normal;
  std::vector<double> y(static_cast<std::size_t>(n));
  double walk = 0.0;
  for (double& v : y) {
    walk += 0.01 * normal(engine);
    v = 0.5 + normal(engine) + walk;
  }
  return y;
}

std::vector<std::int64_t> OctaveAndDense(std::int64_t max_m) {
  std::vector<std::int64_t> ms;
  for (std::int64_t m = 1; m <= max_m; m *= 2) ms.push_back(m);
  for (std::int64_t m : {3, 5, 10, 13, 100, 1000, 4097, 40000, 99999}) {
    if (m <= max_m) ms.push_back(m);
  }
  return ms;
}

// Restores the default kernel when a test that switched it ends.
class KernelSwitch : public ::testing::Test {
 protected:
  void TearDown() override {
    for (const char* name : {"avx512", "avx2+fma", "portable"}) {
      if (UseDifferenceKernelForTesting(name)) break;
    }
  }
};

using DifferenceKernel = KernelSwitch;

TEST_F(DifferenceKernel, VectorVersionsGiveTheSameBitsAndPortableTheSameValues) {
  const std::vector<double> y = Record(300000, 1);
  std::vector<double> phase(y.size() + 1);
  IntegrateMeanRemoved(y, phase);
  for (int order : {2, 3}) {
    const std::vector<std::int64_t> ms = OctaveAndDense(300000 / order);
    std::vector<std::vector<double>> results;
    std::vector<std::string> names;
    for (const char* name : {"avx512", "avx2+fma", "portable"}) {
      if (!UseDifferenceKernelForTesting(name)) continue;
      std::vector<double> sums(ms.size());
      OverlappingDifferenceSums(phase, order, ms, sums);
      results.push_back(sums);
      names.push_back(name);
    }
    ASSERT_FALSE(results.empty());
    for (std::size_t v = 1; v < results.size(); ++v) {
      for (std::size_t k = 0; k < ms.size(); ++k) {
        const double a = results[0][k], b = results[v][k];
        if (names[v] == "portable") {
          // No fused multiply-add: the same sums to rounding.
          EXPECT_NEAR(b, a, 1e-12 * a) << names[v] << " order " << order << " m=" << ms[k];
        } else {
          EXPECT_EQ(b, a) << names[v] << " vs " << names[0] << " order " << order << " m=" << ms[k];
        }
      }
    }
  }
}

// Chain and single-lag loops accumulate the same terms into the same lanes in the same order,
// from any start (the scalar head before a multiple of 16) to any end.
TEST_F(DifferenceKernel, ChainMatchesSingleLagLoopsBitForBit) {
  const std::vector<double> y = Record(5000, 2);
  std::vector<double> x(y.size() + 1);
  IntegrateMeanRemoved(y, x);
  for (const char* name : {"avx512", "avx2+fma", "portable"}) {
    if (!UseDifferenceKernelForTesting(name)) continue;
    for (int count = 1; count <= kMaxChain; ++count) {
      const std::int64_t m = 3;
      const std::int64_t lo = 7, hi = 5000 - (m << count) - 3;
      std::vector<Lanes> chain(static_cast<std::size_t>(count), Lanes{});
      std::vector<Lanes*> pointers;
      for (Lanes& l : chain) pointers.push_back(&l);
      AccumulateSquaredSecondDifferencesChain(x.data(), m, count, lo, hi, pointers.data());
      for (int j = 0; j < count; ++j) {
        Lanes single{};
        AccumulateSquaredDifferences(x.data(), 2, m << j, lo, 100, &single);
        AccumulateSquaredDifferences(x.data(), 2, m << j, 100, hi, &single);
        EXPECT_EQ(single, chain[static_cast<std::size_t>(j)])
            << name << " count " << count << " lag " << (m << j);
      }
    }
  }
}

TEST(PhaseIntegral, PiecesStartingAtMultiplesOfEightGiveOneCallsBits) {
  const std::vector<double> y = Record(1003, 3);
  std::vector<double> whole(y.size() + 1), pieces(y.size() + 1);
  IntegrateAbout(y, 0.25, whole);
  pieces[0] = 0.0;
  std::size_t done = 0;
  for (std::size_t next : {std::size_t{8}, std::size_t{40}, std::size_t{512}, y.size()}) {
    ContinueIntegral(std::span(y).subspan(done, next - done), 0.25,
                     std::span(pieces).subspan(done, next - done + 1));
    done = next;
  }
  EXPECT_EQ(pieces, whole);
  // And the integral is the running sum, to rounding.
  double plain = 0.0;
  for (std::size_t k = 0; k < y.size(); ++k) {
    plain += y[k] - 0.25;
    EXPECT_NEAR(whole[k + 1], plain, 1e-12 * (1.0 + std::abs(plain))) << k;
  }
}

TEST(PhaseIntegral, MeanIsAccurate) {
  // 1e6 copies of 0.1 plus one large value; the exact mean of these doubles, in long double.
  std::vector<double> v(1000000, 0.1);
  v[500000] = 1e6;
  const long double exact = (999999.0L * 0.1 + 1e6L) / 1e6L;
  EXPECT_NEAR(MeanOf(v), static_cast<double>(exact), 1e-14);
  EXPECT_EQ(MeanOf({}), 0.0);
  EXPECT_TRUE(std::isnan(MeanOf(std::vector<double>{1.0, std::nan("")})));
}

TEST(OverlappingDifferenceSums, FusedIntegrationGivesTheSameBits) {
  const std::vector<double> y = Record(300000, 4);
  const double mean = MeanOf(y);
  for (int order : {2, 3}) {
    const std::vector<std::int64_t> ms = OctaveAndDense(300000 / order);
    std::vector<double> phase(y.size() + 1), fused_phase(y.size() + 1);
    IntegrateAbout(y, mean, phase);
    std::vector<double> sums(ms.size()), fused(ms.size());
    OverlappingDifferenceSums(phase, order, ms, sums);
    IntegrateAndSumOverlappingDifferences(y, mean, order, ms, fused_phase, fused);
    EXPECT_EQ(fused_phase, phase) << "order " << order;
    EXPECT_EQ(fused, sums) << "order " << order;
  }
}

TEST(AllanFamilyWorkspace, ReuseGivesTheSameBits) {
  const std::vector<double> small = Record(5000, 5), large = Record(70000, 6);
  AllanFamilyWorkspace workspace;
  for (Statistic s : {Statistic::kAllanOverlapping, Statistic::kModifiedAllan, Statistic::kTotal,
                      Statistic::kHadamardNonOverlapping}) {
    AvarOptions options;
    options.statistic = s;
    for (const std::vector<double>* y : {&small, &large, &small}) {
      AvarSummary fresh, reused;
      ASSERT_TRUE(ComputeStatisticValues(options, *y, &fresh));
      ASSERT_TRUE(ComputeStatisticValues(options, *y, &reused, &workspace));
      ASSERT_EQ(fresh.points.size(), reused.points.size());
      for (std::size_t k = 0; k < fresh.points.size(); ++k) {
        EXPECT_EQ(fresh.points[k].value, reused.points[k].value) << StatisticId(s);
      }
    }
  }
}

TEST(AllanFamily, OverflowingSumIsReported) {
  const std::vector<double> y(10, std::numeric_limits<double>::max() / 2);
  AvarSummary summary;
  EXPECT_FALSE(ComputeStatisticValues(AvarOptions{}, y, &summary));
  EXPECT_EQ(summary.message, "rate samples too large: their running sum overflows");
}

}  // namespace
}  // namespace allanlab::estimators
