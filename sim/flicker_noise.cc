#include "sim/flicker_noise.h"

#include <cmath>
#include <list>
#include <memory>
#include <mutex>
#include <numbers>
#include <utility>

#include <boost/random/normal_distribution.hpp>

#include "sim/fft.h"

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
  const std::vector<double> h = KasdinCoefficients(static_cast<std::int64_t>(n));
  std::fill(buffer->data(), buffer->data() + fft_length + 2, 0.0);
  std::copy(h.begin(), h.end(), buffer->data());
  ForwardRealFft(fft_length, *buffer);
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

void FlickerNoise::AddTo(Engine& engine, double, std::span<double> rate) const {
  const std::size_t n = rate.size();
  if (n == 0 || bias_instability_rad_per_s == 0.0) return;
  const std::size_t fft_length = GoodFftSize(2 * n);
  const auto spectrum = KasdinSpectrum(n, fft_length);
  FftBuffer work(fft_length + 2);
  boost::random::normal_distribution<double> normal(0.0, 1.0);
  double* x = work.data();
  for (std::size_t i = 0; i < n; ++i) x[i] = normal(engine);
  std::fill(x + n, x + fft_length + 2, 0.0);
  ForwardRealFft(fft_length, work);
  std::complex<double>* w = work.complex_data();
  const std::complex<double>* h = spectrum->complex_data();
  for (std::size_t k = 0; k <= fft_length / 2; ++k) w[k] *= h[k];
  InverseRealFft(fft_length, work);
  const double scale = bias_instability_rad_per_s / static_cast<double>(fft_length);
  for (std::size_t i = 0; i < n; ++i) rate[i] += scale * x[i];
}

void FlickerNoise::FillAutocovariance(double, std::span<double> r) const {
  const double scale = 2.0 * bias_instability_rad_per_s * bias_instability_rad_per_s / std::numbers::pi;
  long double harmonic_odd = 0.0L;
  for (std::size_t k = 0; k < r.size(); ++k) {
    if (k > 0) harmonic_odd += 1.0L / (2.0L * k - 1.0L);
    r[k] = -scale * static_cast<double>(harmonic_odd);
  }
}

double FlickerNoise::ExpectedAvar(std::int64_t m, double, const RecordShape& shape) const {
  if (bias_instability_rad_per_s == 0.0) return 0.0;
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
