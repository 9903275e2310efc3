#include "experiments/diagnosis/resonance_estimate.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "sim/fft.h"

namespace allanlab::experiments {

std::optional<EffectInstance> EstimateResonance(std::span<const double> y, double tau0, std::string* why) {
  constexpr std::size_t kSegment = 1024;
  if (y.size() < 8 * kSegment) {
    *why = "record too short for a Welch PSD";
    return std::nullopt;
  }
  // Welch: Hann segments with half overlap over at most 2^21 samples, one-sided density.
  const std::size_t n = std::min<std::size_t>(y.size(), std::size_t{1} << 21);
  std::vector<double> window(kSegment);
  double w2 = 0.0;
  for (std::size_t k = 0; k < kSegment; ++k) {
    window[k] = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * static_cast<double>(k) / kSegment);
    w2 += window[k] * window[k];
  }
  std::vector<double> psd(kSegment / 2 + 1, 0.0);
  sim::FftBuffer buffer(kSegment + 2);
  std::size_t segments = 0;
  for (std::size_t start = 0; start + kSegment <= n; start += kSegment / 2, ++segments) {
    double mean = 0.0;
    for (std::size_t k = 0; k < kSegment; ++k) mean += y[start + k];
    mean /= kSegment;
    for (std::size_t k = 0; k < kSegment; ++k) buffer.data()[k] = (y[start + k] - mean) * window[k];
    sim::ForwardRealFft(kSegment, buffer.data());
    for (std::size_t b = 0; b <= kSegment / 2; ++b) psd[b] += std::norm(buffer.complex_data()[b]);
  }
  const double df = 1.0 / (kSegment * tau0);
  for (double& p : psd) p *= 2.0 * tau0 / (w2 * static_cast<double>(segments));
  // Local floor: the median over +-64 bins (a line of a few Hz at 100 Hz spans ~20 bins).
  const std::size_t bins = psd.size();
  std::vector<double> floor(bins);
  for (std::size_t b = 0; b < bins; ++b) {
    const std::size_t lo = b > 64 ? b - 64 : 1, hi = std::min(bins - 1, b + 64);
    std::vector<double> around(psd.begin() + static_cast<std::ptrdiff_t>(lo), psd.begin() + static_cast<std::ptrdiff_t>(hi) + 1);
    std::nth_element(around.begin(), around.begin() + static_cast<std::ptrdiff_t>(around.size() / 2), around.end());
    floor[b] = around[around.size() / 2];
  }
  std::size_t peak = 0;
  double peak_ratio = 0.0;
  for (std::size_t b = 3; b + 2 < bins; ++b) {
    // The line must hold over three adjacent bins (one bin is a sinusoid or chance).
    const double r = std::min({psd[b - 1] / floor[b - 1], psd[b] / floor[b], psd[b + 1] / floor[b + 1]});
    if (r > peak_ratio) {
      peak_ratio = r;
      peak = b;
    }
  }
  if (peak_ratio < 1.5) {
    *why = "no line rises 1.5x above the PSD's floor over three bins";
    return std::nullopt;
  }
  for (std::size_t b = peak - 1; b <= peak + 1; ++b) {
    if (psd[b] > psd[peak]) peak = b;
  }
  const double half = 0.5 * (psd[peak] - floor[peak]);
  std::size_t left = peak, right = peak;
  while (left > 1 && psd[left - 1] - floor[left - 1] > half) --left;
  while (right + 1 < bins && psd[right + 1] - floor[right + 1] > half) ++right;
  const double width_hz = std::max(1.0, static_cast<double>(right - left + 1)) * df;
  const double f0 = static_cast<double>(peak) * df;
  double power = 0.0;
  const auto reach = static_cast<std::size_t>(3 * (right - left + 1));
  for (std::size_t b = peak > reach + 1 ? peak - reach : 1; b <= std::min(bins - 1, peak + reach); ++b) {
    power += std::max(0.0, psd[b] - floor[b]) * df;
  }
  const double zeta = std::clamp(width_hz / (2.0 * f0), 0.005, 0.5);
  return EffectInstance{Effect::kResonance,
                        {{"sigma_rad_per_s", std::sqrt(power)}, {"frequency_hz", f0}, {"damping", zeta}}};
}

}  // namespace allanlab::experiments
