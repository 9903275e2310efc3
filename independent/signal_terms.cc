#include "independent/signal_terms.h"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <vector>

namespace allanlab::independent {
namespace {

// FFTW's planner is not thread-safe.
std::mutex& PlannerMutex() {
  static std::mutex m;
  return m;
}

// x^3/3 - x^4/4 + ... = x - 2 (1 - e^-x) + (1 - e^-2x) / 2, without cancellation for small x.
double IntegralVarianceBracket(double x) {
  if (x > 0.1) return x - 2.0 * (-std::expm1(-x)) + 0.5 * (-std::expm1(-2.0 * x));
  double sum = 0.0, xk = x * x, fact = 2.0;
  for (int k = 3; k <= 14; ++k) {
    xk *= x;
    fact *= k;
    sum += ((k % 2) ? 1.0 : -1.0) * (std::ldexp(1.0, k - 1) - 2.0) / fact * xk;
  }
  return sum;
}

}  // namespace

std::int64_t FlickerPeriod(std::int64_t n) {
  std::int64_t p = 16;
  while (p < 4 * n) p *= 2;
  return p;
}

void AddFlicker(double floor, RandomStream& rng, std::span<double> rate) {
  if (floor <= 0.0 || rate.empty()) return;
  const double b2 = floor * floor * M_PI / (2.0 * std::log(2.0));
  const std::int64_t p = FlickerPeriod(static_cast<std::int64_t>(rate.size()));
  const std::size_t bins = static_cast<std::size_t>(p / 2 + 1);
  fftw_complex* spec = fftw_alloc_complex(bins);
  double* x = fftw_alloc_real(static_cast<std::size_t>(p));
  fftw_plan plan;
  {
    std::lock_guard<std::mutex> lock(PlannerMutex());
    plan = fftw_plan_dft_c2r_1d(static_cast<int>(p), spec, x, FFTW_ESTIMATE);
  }
  spec[0][0] = spec[0][1] = 0.0;
  spec[bins - 1][0] = spec[bins - 1][1] = 0.0;
  // c2r computes sum_k X_k e^{+2 pi i k n / P} over the Hermitian spectrum: bin k and P - k
  // together give 2 Re(X_k e^{i theta}); X_k = a_k (A - i B) / 2 gives a_k (A cos + B sin).
  for (std::size_t k = 1; k + 1 < bins; ++k) {
    const double a = std::sqrt(b2 / (M_PI * static_cast<double>(k)));
    spec[k][0] = 0.5 * a * rng.Normal();
    spec[k][1] = -0.5 * a * rng.Normal();
  }
  fftw_execute(plan);
  for (std::size_t i = 0; i < rate.size(); ++i) rate[i] += x[i];
  {
    std::lock_guard<std::mutex> lock(PlannerMutex());
    fftw_destroy_plan(plan);
  }
  fftw_free(spec);
  fftw_free(x);
}

void AddRandomWalk(double k, double h, RandomStream& rng, std::span<double> rate) {
  if (k <= 0.0) return;
  // Over one interval: increment D ~ N(0, K^2 h), integral J of the walk's departure,
  // Var J = K^2 h^3 / 3, Cov(D, J) = K^2 h^2 / 2.
  const double vd = k * k * h, vj = k * k * h * h * h / 3.0, c = k * k * h * h / 2.0;
  const double sd = std::sqrt(vd), slope = c / vd, sr = std::sqrt(vj - c * c / vd);
  double b = 0.0;
  for (double& y : rate) {
    const double d = sd * rng.Normal();
    const double j = slope * d + sr * rng.Normal();
    y += b + j / h;
    b += d;
  }
}

void AddRamp(double r, double h, std::span<double> rate) {
  if (r == 0.0) return;
  for (std::size_t i = 0; i < rate.size(); ++i) rate[i] += r * (static_cast<double>(i) + 0.5) * h;
}

void AddGaussMarkov(const GaussMarkov& g, double h, RandomStream& rng, std::span<double> rate) {
  if (g.sigma_rad_per_s <= 0.0) return;
  // dx = -x/Tc dt + sqrt(q) dW, q = 2 s^2 / Tc. Over h: x' = phi x + w1, integral
  // I = x Tc (1 - phi) + w2 with Var w1 = s^2 (1 - phi^2), Var w2 = q Tc^3 bracket(h/Tc),
  // Cov = q Tc^2 (1 - phi)^2 / 2.
  const double s2 = g.sigma_rad_per_s * g.sigma_rad_per_s, tc = g.correlation_time_s, x = h / tc;
  const double q = 2.0 * s2 / tc, phi = std::exp(-x), one_minus_phi = -std::expm1(-x);
  const double v1 = s2 * (-std::expm1(-2.0 * x)), v2 = q * tc * tc * tc * IntegralVarianceBracket(x);
  const double c = 0.5 * q * tc * tc * one_minus_phi * one_minus_phi;
  const double s1 = std::sqrt(v1), slope = c / v1, sr = std::sqrt(std::max(0.0, v2 - c * c / v1));
  double state = g.sigma_rad_per_s * rng.Normal();
  for (double& y : rate) {
    const double w1 = s1 * rng.Normal();
    const double w2 = slope * w1 + sr * rng.Normal();
    y += (state * tc * one_minus_phi + w2) / h;
    state = phi * state + w1;
  }
}

void AddTelegraph(const Telegraph& t, double h, RandomStream& rng, std::span<double> rate) {
  if (t.amplitude_rad_per_s <= 0.0) return;
  double level = (rng.Next() >> 63) ? t.amplitude_rad_per_s : -t.amplitude_rad_per_s;
  double next_flip = t.mean_dwell_s * rng.Exponential();  // memoryless: stationary from t = 0
  for (std::size_t i = 0; i < rate.size(); ++i) {
    const double start = static_cast<double>(i) * h, end = start + h;
    double integral = 0.0, at = start;
    while (next_flip < end) {
      integral += level * (next_flip - at);
      at = next_flip;
      level = -level;
      next_flip += t.mean_dwell_s * rng.Exponential();
    }
    integral += level * (end - at);
    rate[i] += integral / h;
  }
}

void AddSinusoid(const Sinusoid& s, double h, RandomStream& rng, std::span<double> rate) {
  const double phase = s.phase_rad ? *s.phase_rad : 2.0 * M_PI * rng.Uniform();
  if (s.amplitude_rad_per_s == 0.0) return;
  const double w = 2.0 * M_PI * s.frequency_hz, scale = s.amplitude_rad_per_s / (w * h);
  for (std::size_t i = 0; i < rate.size(); ++i) {
    const double a = w * static_cast<double>(i) * h + phase;
    // (cos a - cos(a + w h)) = 2 sin(a + w h / 2) sin(w h / 2)
    rate[i] += scale * 2.0 * std::sin(a + 0.5 * w * h) * std::sin(0.5 * w * h);
  }
}

void AddResonance(const Resonance& r, double h, RandomStream& rng, std::span<double> rate) {
  if (r.sigma_rad_per_s <= 0.0) return;
  const double w0 = 2.0 * M_PI * r.frequency_hz, z = r.damping_ratio, a = z * w0, wd = w0 * std::sqrt(1.0 - z * z);
  const double e = std::exp(-a * h), c = std::cos(wd * h), sn = std::sin(wd * h);
  // Transition of (x, v) over h.
  const double f11 = e * (c + a / wd * sn), f12 = e * sn / wd, f21 = -e * w0 * w0 * sn / wd, f22 = e * (c - a / wd * sn);
  // Stationary covariance P = diag(s^2, w0^2 s^2); process noise Qd = P - F P F^T.
  const double p1 = r.sigma_rad_per_s * r.sigma_rad_per_s, p2 = w0 * w0 * p1;
  const double q11 = p1 - (f11 * f11 * p1 + f12 * f12 * p2);
  const double q12 = -(f11 * f21 * p1 + f12 * f22 * p2);
  const double q22 = p2 - (f21 * f21 * p1 + f22 * f22 * p2);
  const double l11 = std::sqrt(std::max(0.0, q11)), l21 = l11 > 0.0 ? q12 / l11 : 0.0;
  const double l22 = std::sqrt(std::max(0.0, q22 - l21 * l21));
  double x = std::sqrt(p1) * rng.Normal(), v = std::sqrt(p2) * rng.Normal();
  for (double& y : rate) {
    y += x;
    const double n1 = rng.Normal(), n2 = rng.Normal();
    const double xn = f11 * x + f12 * v + l11 * n1, vn = f21 * x + f22 * v + l21 * n1 + l22 * n2;
    x = xn;
    v = vn;
  }
}

std::int64_t StepIndex(const BiasStep& b, double h) { return std::llround(b.time_s / h); }

void AddBiasStep(const BiasStep& b, double h, std::span<double> rate) {
  const std::int64_t j = StepIndex(b, h);
  for (std::int64_t i = std::max<std::int64_t>(0, j); i < static_cast<std::int64_t>(rate.size()); ++i) {
    rate[static_cast<std::size_t>(i)] += b.size_rad_per_s;
  }
}

void AddWarmupDrift(const WarmupDrift& d, double h, std::span<double> rate) {
  const double x = h / d.time_constant_s, first = d.amplitude_rad_per_s * (-std::expm1(-x)) / x;
  for (std::size_t i = 0; i < rate.size(); ++i) rate[i] += first * std::exp(-x * static_cast<double>(i));
}

void AddSpikes(const Spikes& s, double h, RandomStream& rng, std::span<double> rate) {
  const double p = s.rate_hz * h;
  if (p <= 0.0 || s.scale_rad_per_s <= 0.0) return;
  for (double& y : rate) {
    const double u = rng.Uniform();
    if (u >= p) continue;
    const double magnitude = s.scale_rad_per_s * std::pow(rng.UniformOpen(), -1.0 / s.tail_index);
    const bool negative = !s.one_sided && (rng.Next() >> 63);
    y += negative ? -magnitude : magnitude;
  }
}

void QuantizeAngle(const AngleQuantizer& q, double h, RandomStream& rng, std::span<double> rate) {
  double residual = q.lsb_rad * rng.Uniform();  // angle not yet reported, in [0, q)
  for (double& y : rate) {
    residual += y * h;
    const double counts = std::floor(residual / q.lsb_rad);
    residual -= counts * q.lsb_rad;
    y = counts * q.lsb_rad / h;
  }
}

void QuantizeRate(const RateQuantizer& q, RandomStream& rng, std::span<double> rate) {
  for (double& y : rate) {
    const double d = q.subtractive_dither ? q.lsb_rad_per_s * (rng.Uniform() - 0.5) : 0.0;
    y = q.lsb_rad_per_s * std::nearbyint((y + d) / q.lsb_rad_per_s) - d;
  }
}

}  // namespace allanlab::independent
