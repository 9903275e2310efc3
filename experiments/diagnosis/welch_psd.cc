#include "experiments/diagnosis/welch_psd.h"

#include <cmath>
#include <complex>
#include <numbers>

#include "sim/fft.h"

namespace allanlab::experiments {

std::vector<double> WelchPsd(std::span<const double> y, std::size_t n, double tau0_s) {
  if (n < 4 || y.size() < n) return {};
  std::vector<double> window(n);
  double window_power = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    window[k] = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * static_cast<double>(k) / static_cast<double>(n));
    window_power += window[k] * window[k];
  }
  std::vector<double> psd(n / 2 + 1, 0.0);
  sim::FftBuffer buffer(n + 2);
  for (std::size_t start = 0; start + n <= y.size(); start += n / 2) {
    // Four partial sums (n a power of two >= 4): a single chain of additions bounded the psd
    // view's cost.
    double lane[4] = {};
    for (std::size_t k = 0; k < n; k += 4) {
      for (std::size_t l = 0; l < 4; ++l) lane[l] += y[start + k + l];
    }
    const double mean = ((lane[0] + lane[1]) + (lane[2] + lane[3])) / static_cast<double>(n);
    for (std::size_t k = 0; k < n; ++k) buffer.data()[k] = (y[start + k] - mean) * window[k];
    sim::ForwardRealFft(n, buffer.data());
    for (std::size_t b = 0; b <= n / 2; ++b) psd[b] += std::norm(buffer.complex_data()[b]);
  }
  const double scale = 2.0 * tau0_s / (window_power * static_cast<double>(WelchSegments(y.size(), n)));
  for (double& p : psd) p *= scale;
  return psd;
}

}  // namespace allanlab::experiments
