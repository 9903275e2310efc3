#include "estimators/lag_products.h"

#include <algorithm>

#include "common/cpu_features.h"
#include "estimators/difference_kernel.h"  // CompensatedSum

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define ALLANLAB_HAVE_VECTOR_LAGS 1
#endif

namespace allanlab::estimators {
namespace {

double Tree(const double* lane) {
  return ((lane[0] + lane[1]) + (lane[2] + lane[3])) + ((lane[4] + lane[5]) + (lane[6] + lane[7]));
}

// The sum of u_j v_j, j < len, in the order the header states, from the partial sums `lane` of
// the products before `from` (a multiple of 8): where a vector loop left off.
double FinishBlock(const double* u, const double* v, std::int64_t from, std::int64_t len, double* lane) {
  std::int64_t j = from;
  for (; j + 8 <= len; j += 8) {
    for (int l = 0; l < 8; ++l) lane[l] += u[j + l] * v[j + l];
  }
  for (; j < len; ++j) lane[0] += u[j] * v[j];
  return Tree(lane);
}

// Products of the block starting at `start` for lag k: j in [start, min(used - k, start + kLagBlock)).
std::int64_t BlockLength(std::int64_t used, std::int64_t start, std::int64_t k) {
  return std::min(used - k, start + kLagBlock) - start;
}

// The block sums at `start` of lags k .. k + count - 1 into sums[0 .. count - 1] (count is the
// function's own), for every lag whose series reaches the block.
using GroupFn = void (*)(const double* a, std::int64_t used, std::int64_t start, std::int64_t k, double* sums);
constexpr int kMaxGroup = 16;

void PortableGroup(const double* a, std::int64_t used, std::int64_t start, std::int64_t k, double* sums) {
  double lane[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  sums[0] = FinishBlock(a + start, a + start + k, 0, BlockLength(used, start, k), lane);
}

#ifdef ALLANLAB_HAVE_VECTOR_LAGS
// The vector groups run the rounds of 8 products that every lag of the group has in the block
// (this length) and leave the rest of each lag's block (in the shorter last block only) to
// FinishBlock.
std::int64_t CommonLength(std::int64_t used, std::int64_t start, std::int64_t k, int count) {
  const std::int64_t shortest = BlockLength(used, start, k + count - 1);
  return shortest > 0 ? shortest / 8 * 8 : 0;
}

// After a group's vector loop: the upper register halves cleared, then each lag's block finished
// from its partials. Without the clearing the SSE code that runs next (the rest of the program is
// built for the baseline) pays for the dirty halves: the portable lag products ran 3.7 times
// slower after the AVX-512 ones.
__attribute__((target("avx"))) void FinishGroup(const double* u, const double* v, std::int64_t used,
                                                std::int64_t start, std::int64_t k, int count, std::int64_t common,
                                                double (*lanes)[8], double* sums) {
  _mm256_zeroupper();
  for (int l = 0; l < count; ++l) sums[l] = FinishBlock(u, v + l, common, BlockLength(used, start, k + l), lanes[l]);
}

template <int kCount>
__attribute__((target("avx2"))) void Avx2Group(const double* a, std::int64_t used, std::int64_t start,
                                               std::int64_t k, double* sums) {
  const double* u = a + start;
  const double* v = u + k;
  const std::int64_t common = CommonLength(used, start, k, kCount);
  // Partials 0-3 in one register and 4-7 in the other; six lags keep 12 sums, the two u
  // registers and a product within the 16 registers.
  __m256d low[kCount], high[kCount];
  for (int l = 0; l < kCount; ++l) low[l] = high[l] = _mm256_setzero_pd();
  for (std::int64_t j = 0; j < common; j += 8) {
    const __m256d u0 = _mm256_loadu_pd(u + j);
    const __m256d u1 = _mm256_loadu_pd(u + j + 4);
    for (int l = 0; l < kCount; ++l) {
      low[l] = _mm256_add_pd(low[l], _mm256_mul_pd(u0, _mm256_loadu_pd(v + l + j)));
      high[l] = _mm256_add_pd(high[l], _mm256_mul_pd(u1, _mm256_loadu_pd(v + l + j + 4)));
    }
  }
  double lanes[kCount][8];
  for (int l = 0; l < kCount; ++l) {
    _mm256_storeu_pd(lanes[l], low[l]);
    _mm256_storeu_pd(lanes[l] + 4, high[l]);
  }
  FinishGroup(u, v, used, start, k, kCount, common, lanes, sums);
}

template <int kCount>
__attribute__((target("avx512f"))) void Avx512Group(const double* a, std::int64_t used, std::int64_t start,
                                                    std::int64_t k, double* sums) {
  const double* u = a + start;
  const double* v = u + k;
  const std::int64_t common = CommonLength(used, start, k, kCount);
  // All eight partials of a lag in one register.
  __m512d acc[kCount];
  for (int l = 0; l < kCount; ++l) acc[l] = _mm512_setzero_pd();
  for (std::int64_t j = 0; j < common; j += 8) {
    const __m512d u8 = _mm512_loadu_pd(u + j);
    for (int l = 0; l < kCount; ++l) acc[l] = _mm512_add_pd(acc[l], _mm512_mul_pd(u8, _mm512_loadu_pd(v + l + j)));
  }
  double lanes[kCount][8];
  for (int l = 0; l < kCount; ++l) _mm512_storeu_pd(lanes[l], acc[l]);
  FinishGroup(u, v, used, start, k, kCount, common, lanes, sums);
}

// Sixteen lags, k + r and k + 8 + r for r < 8: lag k + 8 + r multiplies u_j by the eight values
// lag k + r multiplies u_{j+8} by, so each load serves two lags. With one load per product
// vector most loads of the unaligned series cross a cache line, and those, not the arithmetic,
// set the pace; halving them nearly halves the time. 16 sums, 8 carried loads and the u vector
// fit in the 32 registers.
__attribute__((target("avx512f"))) void Avx512Group16(const double* a, std::int64_t used, std::int64_t start,
                                                      std::int64_t k, double* sums) {
  const double* u = a + start;
  const double* v = u + k;
  const std::int64_t common = CommonLength(used, start, k, 16);
  __m512d near_acc[8], far_acc[8], near[8];
  for (int r = 0; r < 8; ++r) near_acc[r] = far_acc[r] = near[r] = _mm512_setzero_pd();
  if (common > 0) {
    for (int r = 0; r < 8; ++r) near[r] = _mm512_loadu_pd(v + r);
  }
  for (std::int64_t j = 0; j < common; j += 8) {
    const __m512d u8 = _mm512_loadu_pd(u + j);
    for (int r = 0; r < 8; ++r) {
      const __m512d far = _mm512_loadu_pd(v + r + j + 8);  // lag k + 8 + r at j, lag k + r at j + 8
      near_acc[r] = _mm512_add_pd(near_acc[r], _mm512_mul_pd(u8, near[r]));
      far_acc[r] = _mm512_add_pd(far_acc[r], _mm512_mul_pd(u8, far));
      near[r] = far;
    }
  }
  double lanes[16][8];
  for (int r = 0; r < 8; ++r) {
    _mm512_storeu_pd(lanes[r], near_acc[r]);
    _mm512_storeu_pd(lanes[8 + r], far_acc[r]);
  }
  FinishGroup(u, v, used, start, k, 16, common, lanes, sums);
}

// Groups of 9 .. 15 lags: eight, then the rest.
template <int kCount>
void Avx512Split(const double* a, std::int64_t used, std::int64_t start, std::int64_t k, double* sums) {
  Avx512Group<8>(a, used, start, k, sums);
  Avx512Group<kCount - 8>(a, used, start, k + 8, sums + 8);
}

constexpr GroupFn kAvx2Groups[] = {Avx2Group<1>, Avx2Group<2>, Avx2Group<3>,
                                   Avx2Group<4>, Avx2Group<5>, Avx2Group<6>};
constexpr GroupFn kAvx512Groups[] = {Avx512Group<1>,  Avx512Group<2>,  Avx512Group<3>,  Avx512Group<4>,
                                     Avx512Group<5>,  Avx512Group<6>,  Avx512Group<7>,  Avx512Group<8>,
                                     Avx512Split<9>,  Avx512Split<10>, Avx512Split<11>, Avx512Split<12>,
                                     Avx512Split<13>, Avx512Split<14>, Avx512Split<15>, Avx512Group16};
#endif

constexpr GroupFn kPortableGroups[] = {PortableGroup};

// The kernel's functions for groups of 1 .. size lags.
struct Groups {
  const GroupFn* by_count;
  int size;
};

template <std::size_t kSize>
constexpr Groups GroupsOf(const GroupFn (&fns)[kSize]) {
  return {fns, static_cast<int>(kSize)};
}

bool Supports(LagKernel kernel) {
#ifdef ALLANLAB_HAVE_VECTOR_LAGS
  if (kernel == LagKernel::kAvx2) return CpuHasAvx2();
  if (kernel == LagKernel::kAvx512) return CpuHasAvx512f();
#endif
  return kernel == LagKernel::kBest || kernel == LagKernel::kPortable;
}

Groups GroupsFor(LagKernel kernel) {
#ifdef ALLANLAB_HAVE_VECTOR_LAGS
  if (kernel == LagKernel::kBest) {
    kernel = Supports(LagKernel::kAvx512) ? LagKernel::kAvx512
             : Supports(LagKernel::kAvx2) ? LagKernel::kAvx2
                                          : LagKernel::kPortable;
  }
  if (kernel == LagKernel::kAvx512 && Supports(kernel)) return GroupsOf(kAvx512Groups);
  if (kernel == LagKernel::kAvx2 && Supports(kernel)) return GroupsOf(kAvx2Groups);
#endif
  (void)kernel;
  return GroupsOf(kPortableGroups);
}

}  // namespace

bool LagKernelRuns(LagKernel kernel) { return Supports(kernel); }

void LagProducts(std::span<const double> a, std::span<double> out, LagKernel kernel) {
  const auto used = static_cast<std::int64_t>(a.size());
  const auto lags = static_cast<std::int64_t>(out.size());
  const Groups groups = GroupsFor(kernel);
  for (std::int64_t k = 0; k < lags; k += groups.size) {
    const int count = static_cast<int>(std::min<std::int64_t>(groups.size, lags - k));
    const GroupFn group = groups.by_count[count - 1];
    CompensatedSum sum[kMaxGroup];
    for (std::int64_t start = 0; start + k < used; start += kLagBlock) {
      double block[kMaxGroup];
      group(a.data(), used, start, k, block);
      for (int l = 0; l < count; ++l) {
        if (start + k + l < used) sum[l].Add(block[l]);
      }
    }
    for (int l = 0; l < count; ++l) out[k + l] = sum[l].Value();
  }
}

}  // namespace allanlab::estimators
