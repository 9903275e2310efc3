#include "independent/allan_forms.h"

#include <algorithm>
#include <cmath>

#include "independent/low_pass_chain.h"
#include "independent/signal_terms.h"

namespace allanlab::independent {

double AvarFromAutocovariance(std::span<const double> r, std::int64_t m) {
  auto at = [&](std::int64_t j) { return j < static_cast<std::int64_t>(r.size()) ? r[static_cast<std::size_t>(j)] : 0.0; };
  double s = static_cast<double>(m) * (at(0) - at(m));
  for (std::int64_t j = 1; j < m; ++j) {
    // lags +j and -j: R_j - R_{m+j} and R_j - R_{|m-j|}
    s += static_cast<double>(m - j) * (2.0 * at(j) - at(m + j) - at(m - j));
  }
  return s / (static_cast<double>(m) * static_cast<double>(m));
}

double GaussMarkovAvar(double sigma, double tc, double tau) {
  const double x = tau / tc;
  double bracket;
  if (x < 1e-3) {
    // 2x - 3 + 4e^-x - e^-2x = 2x^3/3 - x^4/2 + 7x^5/30 - ... (cancellation otherwise)
    bracket = x * x * x * (2.0 / 3.0 - x / 2.0 + 7.0 / 30.0 * x * x);
  } else {
    bracket = 2.0 * x - 3.0 + 4.0 * std::exp(-x) - std::exp(-2.0 * x);
  }
  return sigma * sigma * bracket / (x * x);
}

double SinusoidAvar(double a, double f, double tau) {
  const double x = M_PI * f * tau, s = std::sin(x);
  return a * a * s * s * s * s / (x * x);
}

double FlickerAvar(double floor, std::int64_t m, std::int64_t n) {
  const double b2 = floor * floor * M_PI / (2.0 * std::log(2.0));
  const std::int64_t p = FlickerPeriod(n);
  const double md = static_cast<double>(m), pd = static_cast<double>(p);
  double sum = 0.0;
  for (std::int64_t k = 1; k < p / 2; ++k) {
    const double kd = static_cast<double>(k);
    const double sm = std::sin(M_PI * kd * md / pd), s1 = std::sin(M_PI * kd / pd);
    sum += b2 / (M_PI * kd) * 2.0 * sm * sm * sm * sm / (md * md * s1 * s1);
  }
  return sum;
}

double BiasStepOavar(double s, std::int64_t j, std::int64_t m, std::int64_t n) {
  // Difference starting at k: mean over [k+m, k+2m) minus mean over [k, k+m) of the step at j.
  const std::int64_t count = n - 2 * m + 1;
  auto filled = [&](std::int64_t start) {  // share of [start, start+m) at or after j
    return static_cast<double>(std::clamp<std::int64_t>(start + m - j, 0, m)) / static_cast<double>(m);
  };
  double sum = 0.0;
  for (std::int64_t k = std::max<std::int64_t>(0, j - 2 * m); k <= std::min(count - 1, j); ++k) {
    const double d = s * (filled(k + m) - filled(k));
    sum += d * d;
  }
  return sum / (2.0 * static_cast<double>(count));
}

double WarmupDriftOavar(double a, double td, double tau0, std::int64_t m, std::int64_t n) {
  // Sample k: c e^{-k x}, c = a (1 - e^-x)/x; m-mean from k: c e^{-k x}(1 - e^{-m x}) / (m (1 - e^-x));
  // the difference from k: -c e^{-k x} (1 - e^{-m x})^2 / (m (1 - e^-x)).
  const double x = tau0 / td, md = static_cast<double>(m);
  const double c = a * (-std::expm1(-x)) / x;
  const double g = -std::expm1(-md * x), d0 = c * g * g / (md * (-std::expm1(-x)));
  const std::int64_t count = n - 2 * m + 1;
  // sum_{k<count} e^{-2 k x} = (1 - e^{-2 x count}) / (1 - e^{-2x})
  const double geo = (-std::expm1(-2.0 * x * static_cast<double>(count))) / (-std::expm1(-2.0 * x));
  return d0 * d0 * geo / (2.0 * static_cast<double>(count));
}

double ResonanceAvar(const Resonance& r, double tau0, std::int64_t m) {
  const double w0 = 2.0 * M_PI * r.frequency_hz, a = r.damping_ratio * w0;
  const double wd = w0 * std::sqrt(1.0 - r.damping_ratio * r.damping_ratio);
  std::vector<double> cov(static_cast<std::size_t>(2 * m));
  for (std::size_t j = 0; j < cov.size(); ++j) {
    const double t = static_cast<double>(j) * tau0;
    cov[j] = r.sigma_rad_per_s * r.sigma_rad_per_s * std::exp(-a * t) * (std::cos(wd * t) + a / wd * std::sin(wd * t));
  }
  return AvarFromAutocovariance(cov, m);
}

double SpikesAvar(const Spikes& s, double tau0, std::int64_t m) {
  const double p = s.rate_hz * tau0, al = s.tail_index, a = s.scale_rad_per_s;
  const double ea = a * al / (al - 1.0), ea2 = a * a * al / (al - 2.0);
  const double var = p * ea2 - (s.one_sided ? p * p * ea * ea : 0.0);
  return var / static_cast<double>(m);
}

double WhiteChainAvar(const Recipe& r, std::int64_t m) {
  const double n2 = r.noise.arw_rad_per_sqrt_s * r.noise.arw_rad_per_sqrt_s;
  if (n2 == 0.0) return 0.0;
  if (r.low_pass.design == LowPassDesign::kNone) return n2 / (static_cast<double>(m) * r.sample_period_s());
  const double fs_int = r.rate_hz * r.low_pass.oversampling;
  const std::vector<double> cov = OutputAutocovariance(r.low_pass, fs_int, n2 * fs_int, 2 * m);
  return AvarFromAutocovariance(cov, m);
}

double ExpectedOavar(const Recipe& r, std::int64_t m, std::int64_t n) {
  const double tau0 = r.sample_period_s(), tau = static_cast<double>(m) * tau0;
  double v = WhiteChainAvar(r, m);
  const Noise& z = r.noise;
  if (z.flicker_floor_rad_per_s > 0.0) v += FlickerAvar(z.flicker_floor_rad_per_s, m, n);
  v += z.rrw_rad_per_s_per_sqrt_s * z.rrw_rad_per_s_per_sqrt_s * tau / 3.0;
  v += z.ramp_rad_per_s2 * z.ramp_rad_per_s2 * tau * tau / 2.0;
  if (r.gauss_markov) v += GaussMarkovAvar(r.gauss_markov->sigma_rad_per_s, r.gauss_markov->correlation_time_s, tau);
  if (r.telegraph) v += GaussMarkovAvar(r.telegraph->amplitude_rad_per_s, 0.5 * r.telegraph->mean_dwell_s, tau);
  if (r.sinusoid) v += SinusoidAvar(r.sinusoid->amplitude_rad_per_s, r.sinusoid->frequency_hz, tau);
  if (r.resonance) v += ResonanceAvar(*r.resonance, tau0, m);
  if (r.bias_step) v += BiasStepOavar(r.bias_step->size_rad_per_s, StepIndex(*r.bias_step, tau0), m, n);
  if (r.warmup_drift) {
    v += WarmupDriftOavar(r.warmup_drift->amplitude_rad_per_s, r.warmup_drift->time_constant_s, tau0, m, n);
  }
  if (r.spikes) v += SpikesAvar(*r.spikes, tau0, m);
  if (r.rate_quantizer) v += r.rate_quantizer->lsb_rad_per_s * r.rate_quantizer->lsb_rad_per_s / (12.0 * static_cast<double>(m));
  if (r.angle_quantizer) v += r.angle_quantizer->lsb_rad * r.angle_quantizer->lsb_rad / (4.0 * tau * tau);
  return v;
}

std::vector<double> ExpectedOavar(const Recipe& r, std::span<const std::int64_t> ms, std::int64_t n) {
  std::vector<double> out;
  out.reserve(ms.size());
  for (std::int64_t m : ms) out.push_back(ExpectedOavar(r, m, n));
  return out;
}

bool ExpectedOavarIsExact(const Recipe& r) {
  return !r.angle_quantizer && !(r.rate_quantizer && !r.rate_quantizer->subtractive_dither);
}

}  // namespace allanlab::independent
