#include "estimators/lag_products.h"

#include <algorithm>

#include "estimators/difference_kernel.h"  // CompensatedSum

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define ALLANLAB_HAVE_AVX2_LAGS 1
#endif

namespace allanlab::estimators {
namespace {

double Tree(const double* lane) {
  return ((lane[0] + lane[1]) + (lane[2] + lane[3])) + ((lane[4] + lane[5]) + (lane[6] + lane[7]));
}

// The sum of u_j v_j, j < len, in the order the header states.
double PortableBlock(const double* u, const double* v, std::int64_t len) {
  double lane[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  std::int64_t j = 0;
  for (; j + 8 <= len; j += 8) {
    for (int l = 0; l < 8; ++l) lane[l] += u[j + l] * v[j + l];
  }
  for (; j < len; ++j) lane[0] += u[j] * v[j];
  return Tree(lane);
}

#ifdef ALLANLAB_HAVE_AVX2_LAGS
#define ALLANLAB_AVX2_ONLY __attribute__((target("avx2")))

// Four lags at once, v, v + 1, v + 2, v + 3, over one full block of kLagBlock products (a
// multiple of 8, so no tail). Lanes 0-3 in one register and 4-7 in the other, as PortableBlock.
ALLANLAB_AVX2_ONLY void Avx2Block4(const double* u, const double* v, double* sums) {
  __m256d lo[4], hi[4];
  for (int k = 0; k < 4; ++k) lo[k] = hi[k] = _mm256_setzero_pd();
  for (std::int64_t j = 0; j < kLagBlock; j += 8) {
    const __m256d u0 = _mm256_loadu_pd(u + j);
    const __m256d u1 = _mm256_loadu_pd(u + j + 4);
    for (int k = 0; k < 4; ++k) {
      lo[k] = _mm256_add_pd(lo[k], _mm256_mul_pd(u0, _mm256_loadu_pd(v + k + j)));
      hi[k] = _mm256_add_pd(hi[k], _mm256_mul_pd(u1, _mm256_loadu_pd(v + k + j + 4)));
    }
  }
  for (int k = 0; k < 4; ++k) {
    double lane[8];
    _mm256_storeu_pd(lane, lo[k]);
    _mm256_storeu_pd(lane + 4, hi[k]);
    sums[k] = Tree(lane);
  }
}

bool HaveAvx2() {
  static const bool have = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") != 0;
  }();
  return have;
}
#endif

}  // namespace

void LagProducts(std::span<const double> a, std::span<double> out, bool vector_units) {
  const auto used = static_cast<std::int64_t>(a.size());
  const auto lags = static_cast<std::int64_t>(out.size());
  std::int64_t k = 0;
#ifdef ALLANLAB_HAVE_AVX2_LAGS
  if (vector_units && HaveAvx2()) {
    for (; k + 4 <= lags; k += 4) {
      CompensatedSum sum[4];
      std::int64_t lo = 0;
      // Blocks that are full for all four lags (the shortest series is used - k - 3 long).
      for (; lo + kLagBlock <= used - k - 3; lo += kLagBlock) {
        double block[4];
        Avx2Block4(a.data() + lo, a.data() + lo + k, block);
        for (int l = 0; l < 4; ++l) sum[l].Add(block[l]);
      }
      for (int l = 0; l < 4; ++l) {
        for (std::int64_t b = lo; b + k + l < used; b += kLagBlock) {
          const std::int64_t hi = std::min(used - k - l, b + kLagBlock);
          sum[l].Add(PortableBlock(a.data() + b, a.data() + b + k + l, hi - b));
        }
        out[k + l] = sum[l].Value();
      }
    }
  }
#endif
  for (; k < lags; ++k) {
    CompensatedSum sum;
    for (std::int64_t lo = 0; lo + k < used; lo += kLagBlock) {
      const std::int64_t hi = std::min(used - k, lo + kLagBlock);
      sum.Add(PortableBlock(a.data() + lo, a.data() + lo + k, hi - lo));
    }
    out[k] = sum.Value();
  }
}

}  // namespace allanlab::estimators
