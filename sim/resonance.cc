#include "sim/resonance.h"

#include <algorithm>

#include <cmath>
#include <numbers>
#include <sstream>
#include <vector>

#include <boost/random/normal_distribution.hpp>

namespace allanlab::sim {
namespace {

struct Poles {
  double decay_per_s;  // zeta w0
  double wd_rad_s;     // damped angular frequency
  double sin_gain;     // zeta / sqrt(1 - zeta^2)
};
Poles PolesOf(const Resonance& r) {
  const double w0 = 2.0 * std::numbers::pi * r.frequency_hz;
  const double root = std::sqrt(1.0 - r.damping * r.damping);
  return {r.damping * w0, w0 * root, r.damping / root};
}

}  // namespace

double GeometricAvar(std::int64_t m, std::complex<double> z, std::complex<double> c) {
  const double md = static_cast<double>(m);
  const std::complex<double> q = 1.0 - z;
  if (md * std::abs(q) >= 0.01) {
    // m^2 AVAR = Re[c (m + (2 z (m q - r) - z r^2) / q^2)], r = 1 - z^m (the AR(1) closed form,
    // sim/gauss_markov.cc, with a complex pole).
    const std::complex<double> r = 1.0 - std::pow(z, md);
    const std::complex<double> bracket = md + (2.0 * z * (md * q - r) - z * r * r) / (q * q);
    return std::real(c * bracket) / (md * md);
  }
  // Near z = 1 the bracket cancels: the lag sum of the generalised form Re[c (z^j - 1)].
  std::vector<double> acov(static_cast<std::size_t>(2 * m));
  std::complex<double> zj = 1.0;
  for (std::size_t j = 0; j < acov.size(); ++j) {
    acov[j] = std::real(c * (zj - 1.0));
    zj *= z;
  }
  return AvarFromAutocovariance(m, acov);
}

bool Resonance::IsValid(std::string* why) const {
  if (!CheckNonNegative(sigma_rad_per_s, "resonance sigma", why) ||
      !CheckPositive(frequency_hz, "resonance frequency f0", why)) {
    return false;
  }
  if (!(damping > 0.0 && damping < 1.0)) {
    if (why) {
      std::ostringstream os;
      os << "resonance damping ratio must be in (0, 1) (a lightly damped mode), got " << damping;
      *why = os.str();
    }
    return false;
  }
  return true;
}

void Resonance::AddTo(Engine& engine, double tau0_s, std::span<double> rate) const {
  if (sigma_rad_per_s == 0.0) return;
  const Poles p = PolesOf(*this);
  const double w0 = 2.0 * std::numbers::pi * frequency_hz;
  const double e = std::exp(-p.decay_per_s * tau0_s);
  const double c = std::cos(p.wd_rad_s * tau0_s), s = std::sin(p.wd_rad_s * tau0_s);
  // Transition of (x, v = x'): e^{F tau0}, F = [[0, 1], [-w0^2, -2 zeta w0]].
  const double a11 = e * (c + p.decay_per_s / p.wd_rad_s * s), a12 = e * s / p.wd_rad_s;
  const double a21 = -e * w0 * w0 / p.wd_rad_s * s, a22 = e * (c - p.decay_per_s / p.wd_rad_s * s);
  // Stationary covariance diag(sigma^2, w0^2 sigma^2); innovation Q = P - A P A^T.
  const double px = sigma_rad_per_s * sigma_rad_per_s, pv = w0 * w0 * px;
  const double q11 = px - (a11 * a11 * px + a12 * a12 * pv);
  const double q12 = -(a11 * a21 * px + a12 * a22 * pv);
  const double q22 = pv - (a21 * a21 * px + a22 * a22 * pv);
  const double l11 = std::sqrt(std::max(q11, 0.0));
  const double l21 = l11 > 0.0 ? q12 / l11 : 0.0;
  const double l22 = std::sqrt(std::max(q22 - l21 * l21, 0.0));
  boost::random::normal_distribution<double> normal(0.0, 1.0);
  double x = std::sqrt(px) * normal(engine);
  double v = std::sqrt(pv) * normal(engine);
  for (double& out : rate) {
    out += x;
    const double z1 = normal(engine), z2 = normal(engine);
    const double xn = a11 * x + a12 * v + l11 * z1;
    const double vn = a21 * x + a22 * v + l21 * z1 + l22 * z2;
    x = xn;
    v = vn;
  }
}

void Resonance::FillAutocovariance(double tau0_s, std::span<double> r, std::int64_t first_lag) const {
  const Poles p = PolesOf(*this);
  const double var = sigma_rad_per_s * sigma_rad_per_s;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const double t = static_cast<double>(first_lag + static_cast<std::int64_t>(i)) * tau0_s;
    const double envelope = std::exp(-p.decay_per_s * t);
    if (envelope == 0.0) {
      // The envelope has underflowed, and stays at 0 for every later lag: a record-length fill
      // (the exact theory's) no longer spends a sine and a cosine on each.
      std::fill(r.begin() + static_cast<std::ptrdiff_t>(i), r.end(), 0.0);
      return;
    }
    r[i] = var * envelope * (std::cos(p.wd_rad_s * t) + p.sin_gain * std::sin(p.wd_rad_s * t));
  }
}

Resonance::GeometricForm Resonance::Geometric(double tau0_s) const {
  const Poles p = PolesOf(*this);
  return {sigma_rad_per_s * sigma_rad_per_s * std::complex<double>(1.0, -p.sin_gain),
          std::complex<double>(-p.decay_per_s, p.wd_rad_s) * tau0_s};
}

double Resonance::ExpectedAvar(std::int64_t m, double tau0_s, const RecordShape&) const {
  if (sigma_rad_per_s == 0.0) return 0.0;
  // cos(wd t) + g sin(wd t) = Re[(1 - i g) e^{i wd t}].
  const GeometricForm g = Geometric(tau0_s);
  return GeometricAvar(m, std::exp(g.log_pole), g.weight);
}

double Resonance::AsymptoticAvar(double tau_s) const {
  const Poles p = PolesOf(*this);
  const std::complex<double> x = std::complex<double>(p.decay_per_s, -p.wd_rad_s) * tau_s;
  const std::complex<double> c = sigma_rad_per_s * sigma_rad_per_s * std::complex<double>(1.0, -p.sin_gain);
  // 2x - 3 + 4e^{-x} - e^{-2x} = 2x^3/3 - x^4/2 + ...: the series where the closed form cancels.
  const std::complex<double> bracket =
      std::abs(x) < 1e-3 ? 2.0 * x * x * x / 3.0 - x * x * x * x / 2.0
                         : 2.0 * x - 3.0 + 4.0 * std::exp(-x) - std::exp(-2.0 * x);
  return std::real(c * bracket / (x * x));
}

}  // namespace allanlab::sim
