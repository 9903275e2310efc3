#include "experiments/diagnosis/line_shape.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sim/fft.h"

namespace allanlab::experiments {

std::vector<double> HannPeriodogram(std::span<const double> y, std::size_t* n_out) {
  std::size_t n = 1;
  while (n * 2 <= std::min<std::size_t>(y.size(), std::size_t{1} << 20)) n *= 2;
  *n_out = n;
  if (n < 256) return {};
  sim::FftBuffer buffer(n + 2);
  double mean = 0.0;
  for (std::size_t k = 0; k < n; ++k) mean += y[k];
  mean /= static_cast<double>(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double w = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * static_cast<double>(k) / static_cast<double>(n));
    buffer.data()[k] = (y[k] - mean) * w;
  }
  sim::ForwardRealFft(n, buffer.data());
  std::vector<double> power(n / 2 + 1);
  for (std::size_t b = 0; b <= n / 2; ++b) power[b] = std::norm(buffer.complex_data()[b]);
  return power;
}

double LineLobeShare(std::span<const double> rate, double tau0_s, double frequency_hz, double line_halfwidth_hz) {
  std::size_t n = 0;
  const std::vector<double> power = HannPeriodogram(rate, &n);
  if (power.empty()) return 0.0;
  const double bin_hz = 1.0 / (static_cast<double>(n) * tau0_s);
  const auto last = static_cast<std::ptrdiff_t>(power.size()) - 1;
  const auto centre = static_cast<std::ptrdiff_t>(std::llround(frequency_hz / bin_hz));
  const auto w = static_cast<std::ptrdiff_t>(std::max(8.0, std::ceil(line_halfwidth_hz / bin_hz)));
  std::ptrdiff_t peak = std::clamp<std::ptrdiff_t>(centre, 1, last - 1);
  for (std::ptrdiff_t b = std::max<std::ptrdiff_t>(1, centre - w); b <= std::min(last - 1, centre + w); ++b) {
    if (power[b] > power[peak]) peak = b;
  }
  std::vector<double> flanks;
  for (std::ptrdiff_t d = 2 * w + 1; d <= 4 * w; ++d) {
    if (peak - d >= 1) flanks.push_back(power[peak - d]);
    if (peak + d <= last) flanks.push_back(power[peak + d]);
  }
  if (flanks.empty()) return 0.0;
  std::nth_element(flanks.begin(), flanks.begin() + static_cast<std::ptrdiff_t>(flanks.size() / 2), flanks.end());
  // The median of exponentially distributed bins is ln 2 of their mean.
  const double floor = flanks[flanks.size() / 2] / std::numbers::ln2;
  double lobe = 0.0, total = 0.0;
  for (std::ptrdiff_t b = std::max<std::ptrdiff_t>(1, peak - 2 * w); b <= std::min(last, peak + 2 * w); ++b) {
    total += power[b] - floor;
    if (std::abs(b - peak) <= 2) lobe += power[b] - floor;
  }
  return total > 0.0 ? std::clamp(lobe / total, 0.0, 1.0) : 0.0;
}

}  // namespace allanlab::experiments
