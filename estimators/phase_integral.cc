#include "estimators/phase_integral.h"

#include <cstdint>

#include "common/cpu_features.h"
#include "estimators/difference_kernel.h"  // Lanes, CompensatedSum

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define ALLANLAB_HAVE_AVX2_SCAN 1
#endif

namespace allanlab::estimators {
namespace {

// Samples per compensated flush of the lane sums in MeanOf.
constexpr std::int64_t kMeanBlock = 4096;

void PortableIntegrate(const double* v, std::int64_t n, double reference, double* out) {
  double acc = out[0];
  for (std::int64_t k = 0; k < n; ++k) {
    acc += v[k] - reference;
    out[k + 1] = acc;
  }
}

#ifdef ALLANLAB_HAVE_AVX2_SCAN
// [a0, a1, a2, a3] -> [a0, a0+a1, a0+a1+a2, a0+a1+a2+a3]
__attribute__((target("avx2"))) inline __m256d Scan4(__m256d a) {
  const __m256d shifted1 =
      _mm256_blend_pd(_mm256_permute4x64_pd(a, 0x90), _mm256_setzero_pd(), 0x1);
  a = _mm256_add_pd(a, shifted1);
  return _mm256_add_pd(a, _mm256_permute2f128_pd(a, a, 0x08));
}

// Eight samples per step: two in-register scans of four, and one addition on the loop-carried
// chain instead of eight.
__attribute__((target("avx2"))) void Avx2Integrate(const double* v, std::int64_t n,
                                                   double reference, double* out) {
  const __m256d ref = _mm256_set1_pd(reference);
  __m256d carry = _mm256_set1_pd(out[0]);
  std::int64_t k = 0;
  for (; k + 8 <= n; k += 8) {
    __m256d a = Scan4(_mm256_sub_pd(_mm256_loadu_pd(v + k), ref));
    __m256d b = Scan4(_mm256_sub_pd(_mm256_loadu_pd(v + k + 4), ref));
    b = _mm256_add_pd(b, _mm256_permute4x64_pd(a, 0xFF));
    _mm256_storeu_pd(out + k + 1, _mm256_add_pd(a, carry));
    _mm256_storeu_pd(out + k + 5, _mm256_add_pd(b, carry));
    carry = _mm256_add_pd(carry, _mm256_permute4x64_pd(b, 0xFF));
  }
  double acc = out[k];
  for (; k < n; ++k) {
    acc += v[k] - reference;
    out[k + 1] = acc;
  }
}
#endif

}  // namespace

double MeanOf(std::span<const double> values) {
  const auto n = static_cast<std::int64_t>(values.size());
  if (n == 0) return 0.0;
  CompensatedSum total;
  for (std::int64_t start = 0; start < n; start += kMeanBlock) {
    const std::int64_t end = start + kMeanBlock < n ? start + kMeanBlock : n;
    Lanes lanes{};
    std::int64_t k = start;
    for (; k + kLanes <= end; k += kLanes) {
      for (int l = 0; l < kLanes; ++l) lanes[l] += values[k + l];
    }
    for (; k < end; ++k) lanes[k % kLanes] += values[k];
    total.Add(SumLanes(lanes));
  }
  return total.Value() / static_cast<double>(n);
}

double ReferenceLevel(std::span<const double> values) {
  const std::size_t n = values.size();
  if (n == 0) return 0.0;
  const std::size_t stride = (n + kReferenceSamples - 1) / kReferenceSamples;
  CompensatedSum sum;
  std::size_t count = 0;
  for (std::size_t k = 0; k < n; k += stride, ++count) sum.Add(values[k]);
  return sum.Value() / static_cast<double>(count);
}

void ContinueIntegral(std::span<const double> values, double reference, std::span<double> out) {
  const auto n = static_cast<std::int64_t>(values.size());
#ifdef ALLANLAB_HAVE_AVX2_SCAN
  if (CpuHasAvx2()) {
    Avx2Integrate(values.data(), n, reference, out.data());
    return;
  }
#endif
  PortableIntegrate(values.data(), n, reference, out.data());
}

void IntegrateAbout(std::span<const double> values, double reference, std::span<double> out) {
  out[0] = 0.0;
  ContinueIntegral(values, reference, out);
}

void IntegrateMeanRemoved(std::span<const double> rate, std::span<double> phase) {
  IntegrateAbout(rate, MeanOf(rate), phase);
}

}  // namespace allanlab::estimators
