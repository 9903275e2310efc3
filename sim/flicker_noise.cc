#include "sim/flicker_noise.h"

#include <cmath>
#include <list>
#include <memory>
#include <mutex>
#include <numbers>
#include <utility>

#include <boost/random/normal_distribution.hpp>

#include "sim/fft.h"
#include "sim/kasdin_finite_record.h"

namespace allanlab::sim {
namespace {

struct CachedSpectrum {
  std::size_t record_length = 0;
  std::size_t fft_length = 0;
  std::shared_ptr<const FftBuffer> spectrum;
};

// Spectrum of the zero-padded Kasdin filter for one record length. Monte Carlo trials reuse it
// (one FFT of three saved); a small LRU bounds the memory when lengths vary.
std::shared_ptr<const FftBuffer> KasdinSpectrum(std::size_t n, std::size_t fft_length) {
  static std::mutex mutex;
  static std::list<CachedSpectrum> cache;
  constexpr std::size_t kCapacity = 2;
  {
    std::lock_guard<std::mutex> lock(mutex);
    for (auto it = cache.begin(); it != cache.end(); ++it) {
      if (it->record_length == n && it->fft_length == fft_length) {
        cache.splice(cache.begin(), cache, it);
        return cache.front().spectrum;
      }
    }
  }
  auto buffer = std::make_shared<FftBuffer>(fft_length + 2);
  double* h = buffer->data();  // Kasdin coefficients written in place: no second array
  std::fill(h, h + fft_length + 2, 0.0);
  h[0] = 1.0;
  for (std::size_t k = 1; k < n; ++k) h[k] = h[k - 1] * (static_cast<double>(k) - 0.5) / k;
  ForwardRealFft(fft_length, buffer->data());
  std::lock_guard<std::mutex> lock(mutex);
  cache.push_front({n, fft_length, buffer});
  if (cache.size() > kCapacity) cache.pop_back();
  return buffer;
}

}  // namespace

std::vector<double> KasdinCoefficients(std::int64_t n) {
  std::vector<double> h(static_cast<std::size_t>(std::max<std::int64_t>(n, 0)));
  if (n > 0) h[0] = 1.0;
  for (std::int64_t k = 1; k < n; ++k) h[k] = h[k - 1] * (static_cast<double>(k) - 0.5) / k;
  return h;
}

std::vector<double> CumulativeSum(std::span<const double> p) {
  std::vector<double> s(p.size());
  long double acc = 0.0L;
  for (std::size_t i = 0; i < p.size(); ++i) s[i] = static_cast<double>(acc += p[i]);
  return s;
}

bool FlickerNoise::IsValid(std::string* why) const {
  return CheckNonNegative(bias_instability_rad_per_s, "bias instability B", why);
}

std::size_t FlickerNoise::WorkSize(std::size_t n) { return 2 * GoodFftSize(n) + 2; }

void FlickerNoise::SynthesizeInPlace(Engine& engine, std::size_t n, std::span<double> work) const {
  SynthesizeInPlace(engine, n, work, nullptr, 0);
}

void FlickerNoise::SynthesizeInPlace(Engine& engine, std::size_t n, std::span<double> work, FlickerStreamCache* cache,
                                     std::uint64_t stream_seed) const {
  if (n == 0) return;
  if (bias_instability_rad_per_s == 0.0) {
    std::fill(work.begin(), work.begin() + static_cast<std::ptrdiff_t>(n), 0.0);
    return;
  }
  const std::size_t fft_length = WorkSize(n) - 2;
  const double scale = bias_instability_rad_per_s / static_cast<double>(fft_length);
  double* x = work.data();
  if (cache != nullptr) {
    if (const auto unit = cache->Find(stream_seed, n)) {
      for (std::size_t i = 0; i < n; ++i) x[i] = (*unit)[i] * scale;
      return;
    }
  }
  const auto spectrum = KasdinSpectrum(n, fft_length);
  boost::random::normal_distribution<double> normal(0.0, 1.0);
  for (std::size_t i = 0; i < n; ++i) x[i] = normal(engine);
  std::fill(x + n, x + fft_length + 2, 0.0);
  ForwardRealFft(fft_length, x);
  auto* w = reinterpret_cast<std::complex<double>*>(x);
  const std::complex<double>* h = spectrum->complex_data();
  for (std::size_t k = 0; k <= fft_length / 2; ++k) w[k] = MulFinite(w[k], h[k]);
  InverseRealFft(fft_length, x);
  if (cache != nullptr) cache->Keep(stream_seed, std::vector<double>(x, x + n));
  for (std::size_t i = 0; i < n; ++i) x[i] *= scale;
}

bool FlickerNoise::WriteKept(std::size_t n, std::span<double> out, const FlickerStreamCache& cache,
                             std::uint64_t stream_seed) const {
  if (n == 0 || bias_instability_rad_per_s == 0.0) return false;
  const auto unit = cache.Find(stream_seed, n);
  if (!unit) return false;
  // SynthesizeInPlace's scale for a kept record.
  const double scale = bias_instability_rad_per_s / static_cast<double>(WorkSize(n) - 2);
  for (std::size_t i = 0; i < n; ++i) out[i] = (*unit)[i] * scale;
  return true;
}

void FlickerNoise::AddTo(Engine& engine, double, std::span<double> rate) const {
  const std::size_t n = rate.size();
  if (n == 0 || bias_instability_rad_per_s == 0.0) return;
  FftBuffer work(WorkSize(n));
  SynthesizeInPlace(engine, n, std::span<double>(work.data(), work.size()));
  for (std::size_t i = 0; i < n; ++i) rate[i] += work.data()[i];
}

void FlickerNoise::FillAutocovariance(double, std::span<double> r) const {
  const double scale = 2.0 * bias_instability_rad_per_s * bias_instability_rad_per_s / std::numbers::pi;
  if (const auto harmonic_odd = OddHarmonicSums(r.size())) {
    for (std::size_t k = 0; k < r.size(); ++k) r[k] = -scale * (*harmonic_odd)[k];
    return;
  }
  long double harmonic_odd = 0.0L;  // too long to keep: summed here, the same way
  for (std::size_t k = 0; k < r.size(); ++k) {
    if (k > 0) harmonic_odd += 1.0L / (2.0L * k - 1.0L);
    r[k] = -scale * static_cast<double>(harmonic_odd);
  }
}

// Kept up to 32 MB (the autocovariance of a few million samples); longer ones are not kept.
constexpr std::size_t kMaxKeptHarmonicSums = std::size_t{1} << 22;

std::shared_ptr<const std::vector<double>> OddHarmonicSums(std::size_t n) {
  // The long-double sum is a serial chain of divisions (a record-sized autocovariance for every
  // exact OAVAR curve and block-mean view of a flicker model); it does not depend on B, so it is
  // summed once as far as asked and kept, with its running long double to extend it by.
  // Each thread holds the last vector it saw, so a long enough one is read without the lock.
  thread_local std::shared_ptr<const std::vector<double>> seen;
  if (seen && seen->size() >= n) return seen;
  if (n > kMaxKeptHarmonicSums) return nullptr;
  static std::mutex mutex;
  static std::shared_ptr<const std::vector<double>> kept = std::make_shared<const std::vector<double>>();
  static long double running = 0.0L;
  const std::lock_guard<std::mutex> lock(mutex);
  if (kept->size() < n) {
    auto longer = std::make_shared<std::vector<double>>(*kept);
    longer->reserve(n);
    for (std::size_t k = longer->size(); k < n; ++k) {
      if (k > 0) running += 1.0L / (2.0L * k - 1.0L);
      longer->push_back(static_cast<double>(running));
    }
    kept = std::move(longer);
  }
  seen = kept;
  return kept;
}

double FlickerNoise::ExpectedAvar(std::int64_t m, double, const RecordShape& shape) const {
  if (bias_instability_rad_per_s == 0.0) return 0.0;
  if (shape.estimator == AvarEstimatorKind::kOverlapping) {
    return bias_instability_rad_per_s * bias_instability_rad_per_s *
           KasdinOverlappingAvar(m, shape.num_samples);
  }
  const std::vector<double> s = CumulativeSum(KasdinCoefficients(shape.num_samples));
  return FiniteRecordAvar(s, bias_instability_rad_per_s * bias_instability_rad_per_s, m, 0, shape);
}

double FlickerNoise::StationaryAvar(std::int64_t m) const {
  std::vector<double> r(static_cast<std::size_t>(2 * m));
  FillAutocovariance(1.0, r);
  return AvarFromAutocovariance(m, r);
}

double FlickerNoise::AsymptoticAvar(double) const {
  return 2.0 * std::numbers::ln2 / std::numbers::pi * bias_instability_rad_per_s *
         bias_instability_rad_per_s;
}

}  // namespace allanlab::sim
