#include "estimators/exact_avar_variance.h"

#include <algorithm>
#include <cstdlib>
#include <vector>

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

// sum_{k=1}^{count-1} (count - k) D(k)^2, D(k) = 6V(k) - 4V(k+m) - 4V(|k-m|) + V(k+2m) + V(|k-2m|) the
// fourth difference of the variogram at step m (the overlapping differences' covariance up to the
// scale). D is the second difference of A(j) = V(j+m) - 2V(j) + V(|j-m|), itself a second
// difference: A is formed from V in long double, where V's size (k^3 for a random walk) cancels,
// and kept in double, being of the size of the covariances rather than of V; D and the sum then
// run in double, several times faster than the five long-double terms per k, and no less accurate
// (A's rounding is relative to A, not to V).
// `v(j)` is V(j) as a long double (read from the variogram or from its split: the same value).
template <class Variogram>
long double OverlappingLagSum(const Variogram& v, std::int64_t m, std::int64_t count, std::vector<double>* buffer) {
  const std::int64_t last = count - 1 + m;  // A is read up to k + m
  // Every A(0..last) is written before it is read, so a buffer reused across m needs no clearing.
  const auto size = static_cast<std::size_t>(last + 1);
  if (buffer->size() < size) buffer->resize(size);
  double* a = buffer->data();
  for (std::int64_t j = 0; j <= last; ++j) {
    a[static_cast<std::size_t>(j)] = static_cast<double>(v(j + m) - 2.0L * v(j) + v(std::llabs(j - m)));
  }
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
    const std::int64_t last = starts.count - 1 + 2 * m;  // the largest lag the sum reads
    MomentScratch own;
    std::vector<double>* buffer = scratch != nullptr ? &scratch->first : &own.first;
    long double lag_sum;
    if (static_cast<std::int64_t>(split.hi.size()) > last) {
      const double* hi = split.hi.data();
      const double* lo = split.lo.data();
      lag_sum = OverlappingLagSum([&](std::int64_t j) { return static_cast<long double>(hi[j]) + lo[j]; }, m,
                                  starts.count, buffer);
    } else {
      lag_sum = OverlappingLagSum(
          [&](std::int64_t j) { return variogram[static_cast<std::size_t>(j)]; }, m, starts.count, buffer);
    }
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
  const std::int64_t count = num_samples - 3 * m + 1;
  if (m < 1 || count < 1) return {};
  // Delta f(j) = f(j + m) - 2 f(j) + f(|j - m|), applied three times to V (symmetric in the lag):
  // the first from V in long double, kept in double as OverlappingLagSum keeps A (its rounding is
  // relative to the second difference, not to V); the next two in double. Every element of a and
  // c is written before it is read, so reused scratch needs no clearing.
  const auto size_a = static_cast<std::size_t>(count + 2 * m);
  MomentScratch own;
  MomentScratch& work = scratch != nullptr ? *scratch : own;
  if (work.first.size() < size_a) work.first.resize(size_a);
  if (work.second.size() < static_cast<std::size_t>(count + m)) work.second.resize(static_cast<std::size_t>(count + m));
  std::vector<double>& a = work.first;
  std::vector<double>& c = work.second;
  auto v = [&](std::int64_t k) { return variogram[static_cast<std::size_t>(std::llabs(k))]; };
  for (std::int64_t j = 0; j < static_cast<std::int64_t>(size_a); ++j) {
    a[static_cast<std::size_t>(j)] = static_cast<double>(v(j + m) - 2.0L * v(j) + v(j - m));
  }
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
