#include "independent/random_stream.h"

#include <cmath>

namespace allanlab::independent {
namespace {

std::uint64_t SplitMix(std::uint64_t& x) {
  std::uint64_t z = (x += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

std::uint64_t Rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

}  // namespace

RandomStream::RandomStream(std::uint64_t seed, std::uint64_t stream, std::uint64_t component) {
  // Three words folded through splitmix so that nearby (seed, stream, component) give unrelated states.
  std::uint64_t x = seed;
  std::uint64_t h = SplitMix(x);
  x = h ^ (stream * 0xD1B54A32D192ED03ULL);
  h = SplitMix(x);
  x = h ^ (component * 0xABC98388FB8FAC03ULL);
  for (auto& w : s_) w = SplitMix(x);
}

std::uint64_t RandomStream::Next() {
  const std::uint64_t result = Rotl(s_[1] * 5, 7) * 9;
  const std::uint64_t t = s_[1] << 17;
  s_[2] ^= s_[0];
  s_[3] ^= s_[1];
  s_[1] ^= s_[2];
  s_[0] ^= s_[3];
  s_[2] ^= t;
  s_[3] = Rotl(s_[3], 45);
  return result;
}

double RandomStream::Uniform() { return static_cast<double>(Next() >> 11) * 0x1.0p-53; }

double RandomStream::UniformOpen() { return (static_cast<double>(Next() >> 12) + 0.5) * 0x1.0p-52; }

double RandomStream::Normal() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  double u, v, s;
  do {
    u = 2.0 * Uniform() - 1.0;
    v = 2.0 * Uniform() - 1.0;
    s = u * u + v * v;
  } while (s >= 1.0 || s == 0.0);
  const double f = std::sqrt(-2.0 * std::log(s) / s);
  spare_ = v * f;
  has_spare_ = true;
  return u * f;
}

double RandomStream::Exponential() { return -std::log(UniformOpen()); }

double RandomStream::StudentT(double dof) {
  // t = Z / sqrt(V / dof), V ~ chi2(dof) = 2 Gamma(dof/2); Gamma by Marsaglia & Tsang (2000).
  const double shape = 0.5 * dof;
  double gamma;
  {
    const double a = shape < 1.0 ? shape + 1.0 : shape;
    const double d = a - 1.0 / 3.0, c = 1.0 / std::sqrt(9.0 * d);
    for (;;) {
      double x, v;
      do {
        x = Normal();
        v = 1.0 + c * x;
      } while (v <= 0.0);
      v = v * v * v;
      const double u = UniformOpen();
      if (std::log(u) < 0.5 * x * x + d - d * v + d * std::log(v)) {
        gamma = d * v;
        break;
      }
    }
    if (shape < 1.0) gamma *= std::pow(UniformOpen(), 1.0 / shape);
  }
  return Normal() / std::sqrt(2.0 * gamma / dof);
}

double RandomStream::Laplace() {
  const double e = Exponential();
  return (Next() >> 63) ? e : -e;
}

}  // namespace allanlab::independent
