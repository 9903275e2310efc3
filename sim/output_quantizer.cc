#include "sim/output_quantizer.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <boost/random/uniform_real_distribution.hpp>

#include "sim/term_common.h"

namespace allanlab::sim {

bool AngleQuantizer::IsValid(std::string* why) const {
  return CheckPositive(lsb_rad, "angle quantizer LSB", why);
}

void AngleQuantizer::Apply(Engine& engine, double tau0_s, std::span<double> rate) const {
  boost::random::uniform_real_distribution<double> uniform(0.0, 1.0);
  // Angle in LSB units; long double keeps the residual exact over long, biased records.
  long double angle_lsb = uniform(engine);
  long double previous_count = std::floor(angle_lsb);
  const long double per_rate = tau0_s / static_cast<long double>(lsb_rad);
  for (double& v : rate) {
    angle_lsb += v * per_rate;
    const long double count = std::floor(angle_lsb);
    v = static_cast<double>((count - previous_count) * lsb_rad / tau0_s);
    previous_count = count;
  }
}

double AngleQuantizer::ApproximateAvar(double tau_s) const {
  return lsb_rad * lsb_rad / (4.0 * tau_s * tau_s);
}

std::vector<double> AngleQuantizer::ErrorAutocovariance(std::span<const double> d,
                                                        double mean_increment_rad) const {
  const double lsb2 = lsb_rad * lsb_rad;
  const double pi = std::numbers::pi, pi2 = pi * pi;
  std::vector<double> out(d.size(), 0.0);
  for (std::size_t j = 0; j < d.size(); ++j) {
    const double dj = std::max(0.0, d[j]) / lsb2;
    const double shift = static_cast<double>(j) * mean_increment_rad / lsb_rad;  // mu(j) in LSB
    if (dj == 0.0) {
      // A still or purely drifting angle: the deterministic sawtooth series in closed form,
      // sum cos(2 pi k f) / (2 pi^2 k^2) = (f^2 - f + 1/6) / 2, f = frac(mu / q).
      const double f = shift - std::floor(shift);
      out[j] = lsb2 * 0.5 * (f * f - f + 1.0 / 6.0);
      continue;
    }
    const double rate = 2.0 * pi2 * dj;
    if (rate > 40.0) continue;  // exp(-40) ~ 4e-18: decorrelated
    double sum = 0.0;
    for (int k = 1; k <= 100000; ++k) {
      const double kk = static_cast<double>(k) * k;
      const double envelope = std::exp(-rate * kk) / kk;
      sum += envelope * std::cos(2.0 * pi * static_cast<double>(k) * shift);
      if (envelope < 1e-17) break;
    }
    out[j] = lsb2 / (2.0 * pi2) * sum;
  }
  return out;
}

double AngleQuantizer::AvarFromError(std::int64_t m, double tau0_s, std::span<const double> e) {
  auto at = [&](std::int64_t j) { return j < static_cast<std::int64_t>(e.size()) ? e[j] : 0.0; };
  const double tau = static_cast<double>(m) * tau0_s;
  return (3.0 * at(0) - 4.0 * at(m) + at(2 * m)) / (tau * tau);
}

std::vector<double> AngleQuantizer::RateErrorAutocovariance(double tau0_s, std::span<const double> e) {
  std::vector<double> out(e.size() > 1 ? e.size() - 1 : 0, 0.0);
  for (std::size_t j = 0; j < out.size(); ++j) {
    const double before = j == 0 ? e[1] : e[j - 1];
    out[j] = (2.0 * e[j] - before - e[j + 1]) / (tau0_s * tau0_s);
  }
  return out;
}

bool RateQuantizer::IsValid(std::string* why) const {
  return CheckPositive(lsb_rad_per_s, "rate quantizer LSB", why);
}

void RateQuantizer::Apply(std::span<double> rate, double offset_lsb) const {
  for (double& v : rate) v = lsb_rad_per_s * std::nearbyint(v / lsb_rad_per_s + offset_lsb);
}

void RateQuantizer::ApplySubtractiveDither(Engine& engine, std::span<double> rate) const {
  boost::random::uniform_real_distribution<double> dither(-0.5, 0.5);
  for (double& v : rate) {
    const double d = dither(engine);
    v = lsb_rad_per_s * (std::nearbyint(v / lsb_rad_per_s + d) - d);
  }
}

double RateQuantizer::ApproximateAvar(std::int64_t m) const {
  return lsb_rad_per_s * lsb_rad_per_s / (12.0 * static_cast<double>(m));
}

std::vector<double> RateQuantizer::ErrorAutocovariance(std::span<const double> r) const {
  const double lsb2 = lsb_rad_per_s * lsb_rad_per_s;
  const double pi2 = std::numbers::pi * std::numbers::pi;
  std::vector<double> out(r.size(), 0.0);
  if (r.empty()) return out;
  out[0] = lsb2 / 12.0;
  if (subtractive_dither) return out;
  // Beyond kMaxK the series is summed as its tail integral; terms below 1e-17 of lsb^2 stop it.
  constexpr int kMaxK = 2000;
  for (std::size_t j = 1; j < r.size(); ++j) {
    const double d = std::max(0.0, 2.0 * (r[0] - r[j])) / lsb2;  // D(j) in lsb^2
    if (d == 0.0) {
      out[j] = lsb2 / 12.0;  // the signal has not moved: the error repeats itself
      continue;
    }
    const double rate = 2.0 * pi2 * d;
    if (rate > 40.0) continue;  // exp(-40) ~ 4e-18: the error has decorrelated
    double sum = 0.0;
    int k = 1;
    for (; k <= kMaxK; ++k) {
      const double kk = static_cast<double>(k) * k;
      const double term = std::exp(-rate * kk) / kk;
      sum += term;
      if (term < 1e-17) break;
    }
    if (k > kMaxK) {
      // sum_{k > K} e^{-a k^2} / k^2 ~ int_K^inf e^{-a x^2} / x^2 dx; for a K^2 << 1 about 1/K.
      sum += std::exp(-rate * kMaxK * kMaxK) / (kMaxK + 0.5);
    }
    out[j] = lsb2 / (2.0 * pi2) * sum;
  }
  return out;
}

}  // namespace allanlab::sim
