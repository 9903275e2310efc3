#include "independent/low_pass_chain.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>

namespace allanlab::independent {
namespace {

// Samples until the slowest pole has decayed by 1e-13: |p|^n < 1e-13.
std::int64_t DecayLength(const Biquad& q) {
  const double disc = q.a1 * q.a1 - 4.0 * q.a2;
  double r;
  if (disc < 0.0) {
    r = std::sqrt(q.a2);
  } else {
    const double s = std::sqrt(disc);
    r = std::max(std::abs(-q.a1 + s), std::abs(-q.a1 - s)) / 2.0;
  }
  if (r <= 0.0) return 3;
  if (r >= 1.0) throw std::invalid_argument("low-pass design is unstable");
  return static_cast<std::int64_t>(std::ceil(std::log(1e-13) / std::log(r))) + 3;
}

std::vector<double> BiquadImpulse(const Biquad& q, std::int64_t length) {
  std::vector<double> h(static_cast<std::size_t>(length), 0.0);
  double x1 = 0, x2 = 0, y1 = 0, y2 = 0;
  for (std::int64_t n = 0; n < length; ++n) {
    const double x = n == 0 ? 1.0 : 0.0;
    const double y = q.b0 * x + q.b1 * x1 + q.b2 * x2 - q.a1 * y1 - q.a2 * y2;
    h[static_cast<std::size_t>(n)] = y;
    x2 = x1;
    x1 = x;
    y2 = y1;
    y1 = y;
  }
  return h;
}

// Convolution with a moving average of length L (mean of the last L values).
std::vector<double> MovingAverage(const std::vector<double>& h, int L) {
  std::vector<double> out(h.size() + static_cast<std::size_t>(L) - 1, 0.0);
  for (std::size_t i = 0; i < h.size(); ++i) {
    for (int k = 0; k < L; ++k) out[i + static_cast<std::size_t>(k)] += h[i] / L;
  }
  return out;
}

void RunBiquad(const Biquad& q, std::span<const double> in, std::vector<double>* out) {
  out->resize(in.size());
  double x1 = 0, x2 = 0, y1 = 0, y2 = 0;
  for (std::size_t n = 0; n < in.size(); ++n) {
    const double x = in[n];
    const double y = q.b0 * x + q.b1 * x1 + q.b2 * x2 - q.a1 * y1 - q.a2 * y2;
    (*out)[n] = y;
    x2 = x1;
    x1 = x;
    y2 = y1;
    y1 = y;
  }
}

// In place: x[n] <- mean of x[n-L+1 .. n] (zeros before the start).
void RunMovingAverage(int L, std::vector<double>* x) {
  std::vector<double> src = *x;
  double sum = 0.0;
  for (std::size_t n = 0; n < src.size(); ++n) {
    sum += src[n];
    if (n >= static_cast<std::size_t>(L)) sum -= src[n - static_cast<std::size_t>(L)];
    (*x)[n] = sum / L;
  }
}

}  // namespace

Biquad DesignBiquad(const LowPass& lp, double fs_int) {
  const double T = 1.0 / fs_int, wc = 2.0 * M_PI * lp.cutoff_hz;
  Biquad q;
  switch (lp.design) {
    case LowPassDesign::kFirstOrderImpulseInvariant: {
      const double a = std::exp(-wc * T);
      q.b0 = 1.0 - a;
      q.a1 = -a;
      break;
    }
    case LowPassDesign::kFirstOrderBilinear: {
      const double k = std::tan(wc * T / 2.0);
      q.b0 = q.b1 = k / (1.0 + k);
      q.a1 = (k - 1.0) / (k + 1.0);
      break;
    }
    case LowPassDesign::kSecondOrderBilinear: {
      const double k = std::tan(wc * T / 2.0), norm = 1.0 / (1.0 + std::sqrt(2.0) * k + k * k);
      q.b0 = k * k * norm;
      q.b1 = 2.0 * q.b0;
      q.b2 = q.b0;
      q.a1 = 2.0 * (k * k - 1.0) * norm;
      q.a2 = (1.0 - std::sqrt(2.0) * k + k * k) * norm;
      break;
    }
    case LowPassDesign::kSecondOrderImpulseInvariant: {
      // Butterworth poles -wc/sqrt2 (1 +- i): h(t) ~ exp(-s t) sin(w t), s = w = wc / sqrt 2;
      // sampled, h[n] ~ r^n sin(n w T): numerator b1 z^-1, scaled to DC gain 1.
      const double s = wc / std::sqrt(2.0), r = std::exp(-s * T);
      q.a1 = -2.0 * r * std::cos(s * T);
      q.a2 = r * r;
      q.b0 = 0.0;
      q.b1 = 1.0 + q.a1 + q.a2;
      break;
    }
    default:
      throw std::invalid_argument("DesignBiquad: not a biquad design");
  }
  return q;
}

std::vector<double> ChainImpulseResponse(const LowPass& lp, double fs_int) {
  const int L = lp.oversampling;
  if (lp.design == LowPassDesign::kCic) {
    std::vector<double> g = {1.0};
    for (int k = 0; k < lp.cic_stages; ++k) g = MovingAverage(g, L);
    return g;
  }
  const Biquad q = DesignBiquad(lp, fs_int);
  std::vector<double> h = BiquadImpulse(q, DecayLength(q));
  if (lp.decimation == Decimation::kAverage) h = MovingAverage(h, L);
  return h;
}

std::int64_t WarmupSamples(const LowPass& lp, double fs_int) {
  return static_cast<std::int64_t>(ChainImpulseResponse(lp, fs_int).size());
}

void FilterAndDecimate(const LowPass& lp, double fs_int, std::span<const double> internal, std::span<double> out) {
  const int L = lp.oversampling;
  const std::size_t warm = static_cast<std::size_t>(WarmupSamples(lp, fs_int));
  if (internal.size() != warm + out.size() * static_cast<std::size_t>(L)) {
    throw std::invalid_argument("FilterAndDecimate: internal length must be warm-up + L * outputs");
  }
  std::vector<double> z;
  if (lp.design == LowPassDesign::kCic) {
    z.assign(internal.begin(), internal.end());
    for (int k = 0; k < lp.cic_stages; ++k) RunMovingAverage(L, &z);
  } else {
    RunBiquad(DesignBiquad(lp, fs_int), internal, &z);
    if (lp.decimation == Decimation::kAverage) RunMovingAverage(L, &z);
  }
  // Output k reads the last internal sample of its period.
  for (std::size_t k = 0; k < out.size(); ++k) out[k] = z[warm + (k + 1) * static_cast<std::size_t>(L) - 1];
}

std::vector<double> OutputAutocovariance(const LowPass& lp, double fs_int, double input_variance,
                                         std::int64_t max_lag) {
  const std::vector<double> g = ChainImpulseResponse(lp, fs_int);
  const std::size_t L = static_cast<std::size_t>(lp.oversampling);
  std::vector<double> r(static_cast<std::size_t>(max_lag) + 1, 0.0);
  for (std::size_t j = 0; j < r.size(); ++j) {
    const std::size_t shift = j * L;
    if (shift >= g.size()) break;
    double s = 0.0;
    for (std::size_t i = 0; i + shift < g.size(); ++i) s += g[i] * g[i + shift];
    r[j] = input_variance * s;
  }
  return r;
}

}  // namespace allanlab::independent
