#include "estimators/exact_avar_variance.h"

#include <algorithm>
#include <cstdlib>
#include <vector>

#include "common/cpu_features.h"

namespace allanlab::estimators {

std::vector<long double> PhaseVariogram(std::span<const double> autocovariance, std::int64_t lags) {
  // Appended, not zeroed then overwritten: one pass over a record-sized array instead of two.
  std::vector<long double> variogram;
  variogram.reserve(static_cast<std::size_t>(std::max<std::int64_t>(lags, 1)));
  variogram.push_back(0.0L);
  long double increment = autocovariance[0];  // V(k+1) - V(k) = R(0) + 2 sum_{j=1}^{k} R(j)
  for (std::int64_t k = 0; k + 1 < lags; ++k) {
    if (k > 0) increment += 2.0L * autocovariance[k];
    variogram.push_back(variogram.back() + increment);
  }
  return variogram;
}

AvarMoments ExactAvarMoments(std::span<const double> autocovariance, std::int64_t m,
                             const sim::RecordShape& shape) {
  const sim::AllanStarts starts = sim::AllanDifferenceStarts(m, shape);
  if (starts.count == 0) return {};
  const std::int64_t max_lag = (starts.count - 1) * starts.stride + 2 * m;
  return ExactAvarMomentsFromVariogram(PhaseVariogram(autocovariance, max_lag + 1), m, shape);
}

namespace {

// Variograms split into double pairs up to this many lags (the pairs double the variogram's
// memory: beyond, the long doubles are read, as before).
constexpr std::size_t kMaxSplitLags = std::size_t{1} << 24;

// V(above) - 2 V(j) + V(below) from the split variogram in double-double arithmetic: the his
// summed with their rounding errors kept (Knuth's TwoSum), the los added, one rounding at the end.
[[gnu::always_inline]] inline double SplitSecondDifference(const double* hi, const double* lo, std::int64_t j,
                                                           std::int64_t above, std::int64_t below) {
  const double x = hi[above], y = hi[below];
  const double s = x + y;  // TwoSum(x, y): s + e == x + y exactly
  const double yy = s - x;
  const double e = (x - (s - yy)) + (y - yy);
  const double z = -2.0 * hi[j];  // exact
  const double t = s + z;  // TwoSum(s, z)
  const double zz = t - s;
  const double f = (s - (t - zz)) + (z - zz);
  return t + ((e + f) + ((lo[above] + lo[below]) - 2.0 * lo[j]));
}

// a[j] for j in [begin, end), all >= m.
[[gnu::always_inline]] inline void SecondDifferences(const double* __restrict hi, const double* __restrict lo,
                                                     std::int64_t m, std::int64_t begin, std::int64_t end,
                                                     double* __restrict a) {
  for (std::int64_t j = begin; j < end; ++j) a[j] = SplitSecondDifference(hi, lo, j, j + m, j - m);
}
// The same loop compiled for AVX2 (four lanes; no FMA, so the same operations and bits). On other
// targets CpuHasAvx2() is false and the baseline loop runs.
#if defined(__x86_64__) && defined(__GNUC__)
#define ALLANLAB_TARGET_AVX2 __attribute__((target("avx2")))
#else
#define ALLANLAB_TARGET_AVX2
#endif
ALLANLAB_TARGET_AVX2 void Avx2SecondDifferences(const double* hi, const double* lo, std::int64_t m,
                                                std::int64_t begin, std::int64_t end, double* a) {
  SecondDifferences(hi, lo, m, begin, end, a);
}
#undef ALLANLAB_TARGET_AVX2

// a[j] = V(j + m) - 2 V(j) + V(|j - m|), j = 0..count-1: the variogram's second difference at step
// m (twice the covariance of two sums of m rate samples j apart). V's size (k^3 for a random
// walk) cancels in it, so it is formed in more than double precision and kept in double, being
// of the size of the covariances rather than of V. From the split variogram (V = hi + lo exactly)
// by SplitSecondDifference: the long doubles' three 80-bit additions per lag were about 70 % of
// the moment sums' time; these double operations vectorise. Without a split, from the long doubles.
void VariogramSecondDifference(std::span<const long double> variogram, const SplitVariogram& split, std::int64_t m,
                               std::int64_t count, double* a) {
  if (static_cast<std::int64_t>(split.hi.size()) < count + m) {
    for (std::int64_t j = 0; j < count; ++j) {
      a[j] = static_cast<double>(variogram[static_cast<std::size_t>(j + m)] - 2.0L * variogram[static_cast<std::size_t>(j)] +
                                 variogram[static_cast<std::size_t>(std::llabs(j - m))]);
    }
    return;
  }
  const double* hi = split.hi.data();
  const double* lo = split.lo.data();
  const std::int64_t reflected = std::min(count, m);
  for (std::int64_t j = 0; j < reflected; ++j) a[j] = SplitSecondDifference(hi, lo, j, j + m, m - j);
  // Beyond the reflection, most of the O(N) work: AVX2 where the CPU has it.
  if (CpuHasAvx2()) {
    Avx2SecondDifferences(hi, lo, m, reflected, count, a);
  } else {
    SecondDifferences(hi, lo, m, reflected, count, a);
  }
}

// sum_{k=1}^{count-1} (count - k) D(k)^2, D(k) = 6V(k) - 4V(k+m) - 4V(|k-m|) + V(k+2m) + V(|k-2m|) the
// fourth difference of the variogram at step m (the overlapping differences' covariance up to the
// scale): D is the second difference of A (VariogramSecondDifference), in double.
long double OverlappingLagSum(std::span<const long double> variogram, const SplitVariogram& split, std::int64_t m,
                              std::int64_t count, std::vector<double>* buffer) {
  // Every A(0..count-1+m) is written before it is read, so a buffer reused across m needs no clearing.
  const auto size = static_cast<std::size_t>(count + m);
  if (buffer->size() < size) buffer->resize(size);
  double* a = buffer->data();
  VariogramSecondDifference(variogram, split, m, count + m, a);
  // Four partial sums in a fixed order: the same bits on every run.
  constexpr int kLanes = 4;
  double lane[kLanes] = {0.0, 0.0, 0.0, 0.0};
  auto term = [&](std::int64_t k, double a_below) {
    const double d = a[static_cast<std::size_t>(k + m)] - 2.0 * a[static_cast<std::size_t>(k)] + a_below;
    return static_cast<double>(count - k) * d * d;
  };
  std::int64_t k = 1;
  for (; k < count && k < m; ++k) lane[k % kLanes] += term(k, a[static_cast<std::size_t>(m - k)]);
  for (; k < count && k % kLanes != 0; ++k) lane[k % kLanes] += term(k, a[static_cast<std::size_t>(k - m)]);
  for (; k + kLanes <= count; k += kLanes) {
    for (int l = 0; l < kLanes; ++l) lane[l] += term(k + l, a[static_cast<std::size_t>(k + l - m)]);
  }
  for (; k < count; ++k) lane[k % kLanes] += term(k, a[static_cast<std::size_t>(k - m)]);
  return (static_cast<long double>(lane[0]) + lane[1]) + (static_cast<long double>(lane[2]) + lane[3]);
}

}  // namespace

SplitVariogram SplitPhaseVariogram(std::span<const long double> variogram) {
  if (variogram.size() > kMaxSplitLags) return {};
  SplitVariogram split;
  split.hi.reserve(variogram.size());
  split.lo.reserve(variogram.size());
  for (const long double v : variogram) {
    const double hi = static_cast<double>(v);
    const double lo = static_cast<double>(v - hi);
    if (!(static_cast<long double>(hi) + lo == v)) return {};
    split.hi.push_back(hi);
    split.lo.push_back(lo);
  }
  return split;
}

AvarMoments ExactAvarMomentsFromVariogram(std::span<const long double> variogram, std::int64_t m,
                                          const sim::RecordShape& shape) {
  return ExactAvarMomentsFromVariogram(variogram, SplitVariogram{}, m, shape);
}

AvarMoments ExactAvarMomentsFromVariogram(std::span<const long double> variogram, const SplitVariogram& split,
                                          std::int64_t m, const sim::RecordShape& shape, MomentScratch* scratch) {
  const sim::AllanStarts starts = sim::AllanDifferenceStarts(m, shape);
  if (starts.count == 0) return {};
  auto v = [&](std::int64_t k) { return variogram[static_cast<std::size_t>(std::llabs(k))]; };
  const long double scale = -1.0L / (2.0L * m * m);
  auto cov_d = [&](std::int64_t k) {  // Cov(D_s, D_{s+k}), D the Allan difference
    return scale * (6.0L * v(k) - 4.0L * v(k + m) - 4.0L * v(k - m) + v(k + 2 * m) + v(k - 2 * m));
  };
  const long double c0 = cov_d(0);
  long double sum = starts.count * c0 * c0;
  if (starts.stride == 1) {
    MomentScratch own;
    std::vector<double>* buffer = scratch != nullptr ? &scratch->first : &own.first;
    // VariogramSecondDifference reads the long doubles where the split is too short.
    const long double lag_sum = OverlappingLagSum(variogram, split, m, starts.count, buffer);
    sum += 2.0L * scale * scale * lag_sum;
  } else {
    for (std::int64_t i = 1; i < starts.count; ++i) {
      const long double c = cov_d(i * starts.stride);
      sum += 2.0L * (starts.count - i) * c * c;
    }
  }
  AvarMoments moments;
  moments.mean = static_cast<double>(0.5L * c0);
  moments.variance = static_cast<double>(sum / (2.0L * starts.count * starts.count));
  return moments;
}

AvarMoments ExactOhvarMomentsFromVariogram(std::span<const long double> variogram, std::int64_t m,
                                           std::int64_t num_samples, MomentScratch* scratch) {
  return ExactOhvarMomentsFromVariogram(variogram, SplitVariogram{}, m, num_samples, scratch);
}

AvarMoments ExactOhvarMomentsFromVariogram(std::span<const long double> variogram, const SplitVariogram& split,
                                           std::int64_t m, std::int64_t num_samples, MomentScratch* scratch) {
  const std::int64_t count = num_samples - 3 * m + 1;
  if (m < 1 || count < 1) return {};
  // Delta f(j) = f(j + m) - 2 f(j) + f(|j - m|), applied three times to V (symmetric in the lag):
  // the first by VariogramSecondDifference, as OverlappingLagSum forms A (its rounding is relative
  // to the second difference, not to V); the next two in double. Every element of a and c is
  // written before it is read, so reused scratch needs no clearing.
  const auto size_a = static_cast<std::size_t>(count + 2 * m);
  MomentScratch own;
  MomentScratch& work = scratch != nullptr ? *scratch : own;
  if (work.first.size() < size_a) work.first.resize(size_a);
  if (work.second.size() < static_cast<std::size_t>(count + m)) work.second.resize(static_cast<std::size_t>(count + m));
  std::vector<double>& a = work.first;
  std::vector<double>& c = work.second;
  VariogramSecondDifference(variogram, split, m, static_cast<std::int64_t>(size_a), a.data());
  auto second_difference = [m](const std::vector<double>& f, std::int64_t j) {
    return f[static_cast<std::size_t>(j + m)] - 2.0 * f[static_cast<std::size_t>(j)] +
           f[static_cast<std::size_t>(std::llabs(j - m))];
  };
  for (std::int64_t j = 0; j < count + m; ++j) c[static_cast<std::size_t>(j)] = second_difference(a, j);
  const double scale = 1.0 / (12.0 * static_cast<double>(m) * static_cast<double>(m));
  const double c0 = scale * second_difference(c, 0);
  long double lag_sum = 0.0L;  // sum_{k=1}^{T-1} (T - k) Cov(k)^2, in order: the same bits every run
  for (std::int64_t k = 1; k < count; ++k) {
    const double cov = scale * second_difference(c, k);
    lag_sum += static_cast<long double>(static_cast<double>(count - k) * cov * cov);
  }
  AvarMoments moments;
  moments.mean = c0;
  const long double t = static_cast<long double>(count);
  moments.variance = static_cast<double>(2.0L * (t * c0 * c0 + 2.0L * lag_sum) / (t * t));
  return moments;
}

}  // namespace allanlab::estimators
