#include "estimators/difference_kernel.h"

#include <algorithm>
#include <cstdlib>
#include <string_view>
#include <vector>

#include "common/cpu_features.h"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define ALLANLAB_HAVE_AVX2_KERNEL 1
#endif

namespace allanlab::estimators {
namespace {

// ---- Portable: 16 independent lanes, which the compiler vectorises with whatever SIMD the
// baseline target has. No fma here: emulated fma would be slower than the whole pass.

inline double PortableD1(const double* x, std::int64_t t, std::int64_t m) {
  return x[t + m] - x[t];
}
inline double PortableD2(const double* x, std::int64_t t, std::int64_t m) {
  return (x[t] + x[t + 2 * m]) - (x[t + m] + x[t + m]);
}
inline double PortableD3(const double* x, std::int64_t t, std::int64_t m) {
  return (x[t + 3 * m] - x[t]) - 3.0 * (x[t + 2 * m] - x[t + m]);
}

template <int kOrder>
inline double PortableD(const double* x, std::int64_t t, std::int64_t m) {
  if constexpr (kOrder == 1) {
    return PortableD1(x, t, m);
  } else if constexpr (kOrder == 2) {
    return PortableD2(x, t, m);
  } else {
    return PortableD3(x, t, m);
  }
}

template <int kOrder>
void PortableAccumulate(const double* x, std::int64_t m, std::int64_t lo, std::int64_t hi,
                        Lanes* lanes) {
  Lanes acc = *lanes;
  std::int64_t t = lo;
  for (; t < hi && t % kLanes != 0; ++t) {
    const double d = PortableD<kOrder>(x, t, m);
    acc[t % kLanes] += d * d;
  }
  for (; t + kLanes <= hi; t += kLanes) {
    for (int l = 0; l < kLanes; ++l) {
      const double d = PortableD<kOrder>(x, t + l, m);
      acc[l] += d * d;
    }
  }
  for (; t < hi; ++t) {
    const double d = PortableD<kOrder>(x, t, m);
    acc[t % kLanes] += d * d;
  }
  *lanes = acc;
}

void PortableAccumulate1(const double* x, std::int64_t m, std::int64_t lo, std::int64_t hi,
                         Lanes* lanes) {
  PortableAccumulate<1>(x, m, lo, hi, lanes);
}
void PortableAccumulate2(const double* x, std::int64_t m, std::int64_t lo, std::int64_t hi,
                         Lanes* lanes) {
  PortableAccumulate<2>(x, m, lo, hi, lanes);
}
void PortableAccumulate3(const double* x, std::int64_t m, std::int64_t lo, std::int64_t hi,
                         Lanes* lanes) {
  PortableAccumulate<3>(x, m, lo, hi, lanes);
}
void PortableChain(const double* x, std::int64_t m, int count, std::int64_t lo, std::int64_t hi,
                   Lanes* const* lanes) {
  for (int j = 0; j < count; ++j) PortableAccumulate<2>(x, m << j, lo, hi, lanes[j]);
}

#ifdef ALLANLAB_HAVE_AVX2_KERNEL
// ---- AVX2 + FMA. The vector and the scalar (head/tail) code compute D_t with the same fused
// operations, so a term's value does not depend on where a range starts.
#define ALLANLAB_AVX2 __attribute__((target("avx2,fma")))

ALLANLAB_AVX2 inline double ScalarD1(const double* x, std::int64_t t, std::int64_t m) {
  return x[t + m] - x[t];
}
ALLANLAB_AVX2 inline double ScalarD2(const double* x, std::int64_t t, std::int64_t m) {
  return std::fma(x[t + m], -2.0, x[t] + x[t + 2 * m]);
}
ALLANLAB_AVX2 inline double ScalarD3(const double* x, std::int64_t t, std::int64_t m) {
  return std::fma(x[t + 2 * m] - x[t + m], -3.0, x[t + 3 * m] - x[t]);
}
ALLANLAB_AVX2 inline __m256d VectorD1(const double* p, std::int64_t m) {
  return _mm256_sub_pd(_mm256_loadu_pd(p + m), _mm256_loadu_pd(p));
}
ALLANLAB_AVX2 inline __m256d VectorD2(const double* p, std::int64_t m) {
  return _mm256_fmadd_pd(_mm256_loadu_pd(p + m), _mm256_set1_pd(-2.0),
                         _mm256_add_pd(_mm256_loadu_pd(p), _mm256_loadu_pd(p + 2 * m)));
}
ALLANLAB_AVX2 inline __m256d VectorD3(const double* p, std::int64_t m) {
  const __m256d outer = _mm256_sub_pd(_mm256_loadu_pd(p + 3 * m), _mm256_loadu_pd(p));
  const __m256d inner = _mm256_sub_pd(_mm256_loadu_pd(p + 2 * m), _mm256_loadu_pd(p + m));
  return _mm256_fmadd_pd(inner, _mm256_set1_pd(-3.0), outer);
}

template <int kOrder>
ALLANLAB_AVX2 inline double ScalarD(const double* x, std::int64_t t, std::int64_t m) {
  if constexpr (kOrder == 1) {
    return ScalarD1(x, t, m);
  } else if constexpr (kOrder == 2) {
    return ScalarD2(x, t, m);
  } else {
    return ScalarD3(x, t, m);
  }
}
template <int kOrder>
ALLANLAB_AVX2 inline __m256d VectorD(const double* p, std::int64_t m) {
  if constexpr (kOrder == 1) {
    return VectorD1(p, m);
  } else if constexpr (kOrder == 2) {
    return VectorD2(p, m);
  } else {
    return VectorD3(p, m);
  }
}

// Four accumulators of four lanes: enough independent FMA chains to hide their latency.
template <int kOrder>
ALLANLAB_AVX2 void Avx2Accumulate(const double* x, std::int64_t m, std::int64_t lo, std::int64_t hi,
                                  Lanes* lanes) {
  double* acc = lanes->data();
  std::int64_t t = lo;
  for (; t < hi && t % kLanes != 0; ++t) {
    const double d = ScalarD<kOrder>(x, t, m);
    acc[t % kLanes] = std::fma(d, d, acc[t % kLanes]);
  }
  if (t + kLanes <= hi) {
    __m256d a0 = _mm256_loadu_pd(acc), a1 = _mm256_loadu_pd(acc + 4);
    __m256d a2 = _mm256_loadu_pd(acc + 8), a3 = _mm256_loadu_pd(acc + 12);
    for (; t + kLanes <= hi; t += kLanes) {
      const __m256d d0 = VectorD<kOrder>(x + t, m), d1 = VectorD<kOrder>(x + t + 4, m);
      const __m256d d2 = VectorD<kOrder>(x + t + 8, m), d3 = VectorD<kOrder>(x + t + 12, m);
      a0 = _mm256_fmadd_pd(d0, d0, a0);
      a1 = _mm256_fmadd_pd(d1, d1, a1);
      a2 = _mm256_fmadd_pd(d2, d2, a2);
      a3 = _mm256_fmadd_pd(d3, d3, a3);
    }
    _mm256_storeu_pd(acc, a0);
    _mm256_storeu_pd(acc + 4, a1);
    _mm256_storeu_pd(acc + 8, a2);
    _mm256_storeu_pd(acc + 12, a3);
  }
  for (; t < hi; ++t) {
    const double d = ScalarD<kOrder>(x, t, m);
    acc[t % kLanes] = std::fma(d, d, acc[t % kLanes]);
  }
}

ALLANLAB_AVX2 void Avx2Accumulate1(const double* x, std::int64_t m, std::int64_t lo,
                                   std::int64_t hi, Lanes* lanes) {
  Avx2Accumulate<1>(x, m, lo, hi, lanes);
}
ALLANLAB_AVX2 void Avx2Accumulate2(const double* x, std::int64_t m, std::int64_t lo,
                                   std::int64_t hi, Lanes* lanes) {
  Avx2Accumulate<2>(x, m, lo, hi, lanes);
}
ALLANLAB_AVX2 void Avx2Accumulate3(const double* x, std::int64_t m, std::int64_t lo,
                                   std::int64_t hi, Lanes* lanes) {
  Avx2Accumulate<3>(x, m, lo, hi, lanes);
}

ALLANLAB_AVX2 inline void PairScalarStep(const double* x, std::int64_t t, std::int64_t m,
                                         double* acc_a, double* acc_b) {
  const double da = ScalarD2(x, t, m);
  const double db = ScalarD2(x, t, 2 * m);
  acc_a[t % kLanes] = std::fma(da, da, acc_a[t % kLanes]);
  acc_b[t % kLanes] = std::fma(db, db, acc_b[t % kLanes]);
}

ALLANLAB_AVX2 void Avx2Pair(const double* x, std::int64_t m, std::int64_t lo, std::int64_t hi,
                            Lanes* lanes_a, Lanes* lanes_b) {
  double* acc_a = lanes_a->data();
  double* acc_b = lanes_b->data();
  std::int64_t t = lo;
  for (; t < hi && t % kLanes != 0; ++t) PairScalarStep(x, t, m, acc_a, acc_b);
  if (t + kLanes <= hi) {
    __m256d a[4], b[4];
    for (int k = 0; k < 4; ++k) {
      a[k] = _mm256_loadu_pd(acc_a + 4 * k);
      b[k] = _mm256_loadu_pd(acc_b + 4 * k);
    }
    const __m256d minus2 = _mm256_set1_pd(-2.0);
    for (; t + kLanes <= hi; t += kLanes) {
      for (int k = 0; k < 4; ++k) {
        const double* p = x + t + 4 * k;
        const __m256d x0 = _mm256_loadu_pd(p), x1 = _mm256_loadu_pd(p + m);
        const __m256d x2 = _mm256_loadu_pd(p + 2 * m), x4 = _mm256_loadu_pd(p + 4 * m);
        const __m256d da = _mm256_fmadd_pd(x1, minus2, _mm256_add_pd(x0, x2));
        const __m256d db = _mm256_fmadd_pd(x2, minus2, _mm256_add_pd(x0, x4));
        a[k] = _mm256_fmadd_pd(da, da, a[k]);
        b[k] = _mm256_fmadd_pd(db, db, b[k]);
      }
    }
    for (int k = 0; k < 4; ++k) {
      _mm256_storeu_pd(acc_a + 4 * k, a[k]);
      _mm256_storeu_pd(acc_b + 4 * k, b[k]);
    }
  }
  for (; t < hi; ++t) PairScalarStep(x, t, m, acc_a, acc_b);
}

ALLANLAB_AVX2 void Avx2Chain(const double* x, std::int64_t m, int count, std::int64_t lo,
                             std::int64_t hi, Lanes* const* lanes) {
  int j = 0;
  for (; j + 1 < count; j += 2) Avx2Pair(x, m << j, lo, hi, lanes[j], lanes[j + 1]);
  if (j < count) Avx2Accumulate<2>(x, m << j, lo, hi, lanes[j]);
}

// ---- AVX-512: the whole chain in one loop. Sixteen lanes per lag are two registers, so eight
// lags fit with their loads in the 32 registers.
#define ALLANLAB_AVX512 __attribute__((target("avx512f,avx2,fma")))

template <int kCount>
ALLANLAB_AVX512 void Avx512ChainOf(const double* x, std::int64_t m, std::int64_t lo,
                                   std::int64_t hi, Lanes* const* lanes) {
  std::int64_t t = lo;
  for (; t < hi && t % kLanes != 0; ++t) {
    for (int j = 0; j < kCount; ++j) {
      const double d = ScalarD2(x, t, m << j);
      double& a = (*lanes[j])[t % kLanes];
      a = std::fma(d, d, a);
    }
  }
  if (t + kLanes <= hi) {
    __m512d acc[kCount][2];
    for (int j = 0; j < kCount; ++j) {
      acc[j][0] = _mm512_loadu_pd(lanes[j]->data());
      acc[j][1] = _mm512_loadu_pd(lanes[j]->data() + 8);
    }
    const __m512d minus2 = _mm512_set1_pd(-2.0);
    for (; t + kLanes <= hi; t += kLanes) {
      for (int h = 0; h < 2; ++h) {
        const double* p = x + t + 8 * h;
        const __m512d x0 = _mm512_loadu_pd(p);
        __m512d near = _mm512_loadu_pd(p + m);  // x_{t + 2^j m}
        for (int j = 0; j < kCount; ++j) {
          const __m512d far = _mm512_loadu_pd(p + (m << (j + 1)));
          const __m512d d = _mm512_fmadd_pd(near, minus2, _mm512_add_pd(x0, far));
          acc[j][h] = _mm512_fmadd_pd(d, d, acc[j][h]);
          near = far;
        }
      }
    }
    for (int j = 0; j < kCount; ++j) {
      _mm512_storeu_pd(lanes[j]->data(), acc[j][0]);
      _mm512_storeu_pd(lanes[j]->data() + 8, acc[j][1]);
    }
  }
  for (; t < hi; ++t) {
    for (int j = 0; j < kCount; ++j) {
      const double d = ScalarD2(x, t, m << j);
      double& a = (*lanes[j])[t % kLanes];
      a = std::fma(d, d, a);
    }
  }
}

ALLANLAB_AVX512 void Avx512Chain(const double* x, std::int64_t m, int count, std::int64_t lo,
                                 std::int64_t hi, Lanes* const* lanes) {
  switch (count) {
    case 1:
      return Avx512ChainOf<1>(x, m, lo, hi, lanes);
    case 2:
      return Avx512ChainOf<2>(x, m, lo, hi, lanes);
    case 3:
      return Avx512ChainOf<3>(x, m, lo, hi, lanes);
    case 4:
      return Avx512ChainOf<4>(x, m, lo, hi, lanes);
    case 5:
      return Avx512ChainOf<5>(x, m, lo, hi, lanes);
    case 6:
      return Avx512ChainOf<6>(x, m, lo, hi, lanes);
    case 7:
      return Avx512ChainOf<7>(x, m, lo, hi, lanes);
    default:
      return Avx512ChainOf<8>(x, m, lo, hi, lanes);
  }
}
#endif  // ALLANLAB_HAVE_AVX2_KERNEL

using AccumulateFn = void (*)(const double*, std::int64_t, std::int64_t, std::int64_t, Lanes*);
using ChainFn = void (*)(const double*, std::int64_t, int, std::int64_t, std::int64_t,
                         Lanes* const*);

struct Kernel {
  AccumulateFn first;
  AccumulateFn second;
  AccumulateFn third;
  ChainFn chain;
  const char* name;
};

// Every version this CPU runs, best first.
std::vector<Kernel> AvailableKernels() {
  std::vector<Kernel> kernels;
#ifdef ALLANLAB_HAVE_AVX2_KERNEL
  if (CpuHasAvx2() && CpuHasFma()) {
    // The single-lag loops stay AVX2: with three loads per term they gain nothing from wider
    // registers; the chain does.
    if (CpuHasAvx512f()) {
      kernels.push_back({Avx2Accumulate1, Avx2Accumulate2, Avx2Accumulate3, Avx512Chain, "avx512"});
    }
    kernels.push_back({Avx2Accumulate1, Avx2Accumulate2, Avx2Accumulate3, Avx2Chain, "avx2+fma"});
  }
#endif
  kernels.push_back(
      {PortableAccumulate1, PortableAccumulate2, PortableAccumulate3, PortableChain, "portable"});
  return kernels;
}

// Chosen at first use: the best one, or the one ALLANLAB_DIFFERENCE_KERNEL names (for
// benchmarking the others on one machine).
const Kernel*& Current() {
  static const std::vector<Kernel> kernels = AvailableKernels();
  static const Kernel* current = [] {
    const char* name = std::getenv("ALLANLAB_DIFFERENCE_KERNEL");
    for (const Kernel& k : kernels) {
      if (name != nullptr && k.name == std::string_view(name)) return &k;
    }
    return &kernels.front();
  }();
  return current;
}

const Kernel& ChosenKernel() { return *Current(); }

}  // namespace

void AccumulateSquaredDifferences(const double* x, int order, std::int64_t m, std::int64_t lo,
                                  std::int64_t hi, Lanes* lanes) {
  if (hi <= lo) return;
  const Kernel& kernel = ChosenKernel();
  const AccumulateFn fn = order == 1 ? kernel.first : order == 2 ? kernel.second : kernel.third;
  fn(x, m, lo, hi, lanes);
}

void AccumulateSquaredSecondDifferencesChain(const double* x, std::int64_t m, int count,
                                             std::int64_t lo, std::int64_t hi,
                                             Lanes* const* lanes) {
  if (hi <= lo) return;
  ChosenKernel().chain(x, m, count, lo, hi, lanes);
}

double SumSquaredDifferences(const double* x, int order, std::int64_t m, std::int64_t lo,
                             std::int64_t hi) {
  constexpr std::int64_t kFlush = 4096;
  CompensatedSum total;
  for (std::int64_t start = lo; start < hi; start += kFlush) {
    Lanes lanes{};
    AccumulateSquaredDifferences(x, order, m, start, std::min(start + kFlush, hi), &lanes);
    total.Add(SumLanes(lanes));
  }
  return total.Value();
}

double SumLanes(const Lanes& lanes) {
  // Pairwise, so that the order is fixed and the rounding small.
  double level[kLanes];
  for (int l = 0; l < kLanes; ++l) level[l] = lanes[l];
  for (int width = kLanes / 2; width >= 1; width /= 2) {
    for (int l = 0; l < width; ++l) level[l] = level[l] + level[l + width];
  }
  return level[0];
}

const char* DifferenceKernelName() { return ChosenKernel().name; }

bool UseDifferenceKernelForTesting(std::string_view name) {
  static const std::vector<Kernel> kernels = AvailableKernels();
  for (const Kernel& k : kernels) {
    if (k.name == name) {
      Current() = &k;
      return true;
    }
  }
  return false;
}

}  // namespace allanlab::estimators
