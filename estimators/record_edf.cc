#include "estimators/record_edf.h"

#include <algorithm>
#include <vector>

#include "estimators/lag_products.h"

namespace allanlab::estimators {
namespace {

constexpr std::int64_t kMaxLagWindow = 256;
constexpr std::int64_t kTermsPerLag = 16;

bool Covered(Statistic s) {
  return s == Statistic::kAllanNonOverlapping || s == Statistic::kAllanOverlapping ||
         s == Statistic::kHadamardNonOverlapping || s == Statistic::kHadamardOverlapping;
}

// Start indices advance by the statistic's stride: 1 for the overlapping estimators, m for the
// non-overlapping ones, whose terms then overlap only at lags of 1 .. d - 1 strides.
std::int64_t Stride(Statistic s, std::int64_t m) { return IsOverlapping(s) ? 1 : m; }

// Differences measured: the estimator's own term count, at most max_terms.
std::int64_t MeasuredTerms(Statistic s, std::int64_t m, std::int64_t n, std::int64_t max_terms) {
  return std::min(TermCount(s, m, n), max_terms);
}

// Lags (in terms) at which two terms of the estimate still share samples: k stride < d m.
std::int64_t LagWindow(Statistic s, std::int64_t m) {
  return (DifferenceOrder(s) * m + Stride(s, m) - 1) / Stride(s, m);
}

// a[j] = the order-kOrder difference at lag m starting at x[j stride]. The overlapping
// estimators' stride of 1 gets its own loop, which the compiler vectorises, in AVX2 where the CPU
// has it (half the instructions of the baseline's SSE2; AVX2 has no fused multiply-add, so the
// same bits).
template <int kOrder>
__attribute__((target_clones("avx2", "default"))) void DifferenceTerms(const double* x, std::int64_t stride, std::int64_t m, std::span<double> a) {
  const auto term = [m](const double* t) {
    if constexpr (kOrder == 2) {
      return (t[2 * m] - t[m]) - (t[m] - t[0]);
    } else {
      return (t[3 * m] - t[0]) - 3.0 * (t[2 * m] - t[m]);
    }
  };
  const auto used = static_cast<std::int64_t>(a.size());
  if (stride == 1) {
    for (std::int64_t j = 0; j < used; ++j) a[static_cast<std::size_t>(j)] = term(x + j);
  } else {
    for (std::int64_t j = 0; j < used; ++j) a[static_cast<std::size_t>(j)] = term(x + j * stride);
  }
}

}  // namespace

bool RecordEdfAvailable(Statistic s, std::int64_t m, std::int64_t n, std::int64_t max_terms) {
  if (!Covered(s) || m < 1 || TermCount(s, m, n) < 2) return false;
  const std::int64_t window = LagWindow(s, m);
  return window <= kMaxLagWindow && kTermsPerLag * window <= MeasuredTerms(s, m, n, max_terms);
}

RecordEdfStretch RecordEdfReads(Statistic s, std::int64_t n, std::int64_t m, std::int64_t max_terms) {
  if (n < 1 || !RecordEdfAvailable(s, m, n, max_terms)) return {};
  const std::int64_t stride = Stride(s, m);
  const std::int64_t used = MeasuredTerms(s, m, n, max_terms);
  const std::int64_t first = (TermCount(s, m, n) - used) / 2;
  return {first * stride, (first + used - 1) * stride + DifferenceOrder(s) * m};
}

double RecordEdf(Statistic s, std::span<const double> phase, std::int64_t m,
                 std::int64_t max_terms) {
  const auto n = static_cast<std::int64_t>(phase.size()) - 1;
  const RecordEdfStretch reads = RecordEdfReads(s, n, m, max_terms);
  if (reads.hi < reads.lo) return 0.0;
  return RecordEdfFromStretch(
      s, n, phase.subspan(static_cast<std::size_t>(reads.lo), static_cast<std::size_t>(reads.hi - reads.lo + 1)), m,
      max_terms);
}

double RecordEdfFromStretch(Statistic s, std::int64_t n, std::span<const double> stretch, std::int64_t m,
                            std::int64_t max_terms) {
  if (n < 1 || !RecordEdfAvailable(s, m, n, max_terms)) return 0.0;
  const int d = DifferenceOrder(s);
  const std::int64_t stride = Stride(s, m);
  const std::int64_t total = TermCount(s, m, n);
  const std::int64_t used = MeasuredTerms(s, m, n, max_terms);
  // The measured terms: a_j = sum_i c_i x_{t + i m}, t = (first + j) stride for the middle
  // `used` terms, binomial c with alternating signs (order 2: 1, -2, 1; order 3: -1, 3, -3, 1);
  // stretch[0] is x_{first stride} (RecordEdfReads). Their buffer is kept per thread from one
  // call to the next: a fresh one (2 MB at the default cap) for every tau costs more in page
  // faults than forming the terms. Every term is written before it is read.
  static thread_local std::vector<double> terms;
  if (terms.size() < static_cast<std::size_t>(used)) terms.resize(static_cast<std::size_t>(used));
  const std::span<double> a(terms.data(), static_cast<std::size_t>(used));
  if (d == 2) {
    DifferenceTerms<2>(stretch.data(), stride, m, a);
  } else {
    DifferenceTerms<3>(stretch.data(), stride, m, a);
  }
  const std::int64_t window = LagWindow(s, m);
  // Raw (not mean-removed) lag products: the estimate averages raw squares, so these are the
  // moments its variance is made of.
  const std::int64_t lags = std::min(window, total - 1);
  std::vector<double> products(static_cast<std::size_t>(lags + 1));
  LagProducts(a, products);
  const auto lag_product = [&](std::int64_t k) {
    return products[static_cast<std::size_t>(k)] / static_cast<double>(used - k);
  };
  const double c0 = lag_product(0);
  if (!(c0 > 0.0)) return 0.0;
  const double big_m = static_cast<double>(total);
  double raw = 1.0;
  for (std::int64_t k = 1; k <= lags; ++k) {
    const double rho = lag_product(k) / c0;
    raw += 2.0 * (1.0 - static_cast<double>(k) / big_m) * rho * rho;
  }
  // E[rho_hat^2] ~ rho^2 + S / M' (Bartlett), so E[raw] ~ S (1 + 2 window / M').
  const double sum = raw / (1.0 + 2.0 * static_cast<double>(window) / static_cast<double>(used));
  return big_m / std::max(sum, 1.0);
}

}  // namespace allanlab::estimators
