#include "experiments/plain_noise.h"

#include <cmath>
#include <random>
#include <stdexcept>

namespace allanlab::experiments {
namespace {

constexpr int kFlickerFirst = -6, kFlickerLast = 40;  // correlation times 2^(j/2) samples

double FlickerCorrelationTime(int j) { return std::exp2(0.5 * j); }

// E[AVAR(m)] of a stationary sequence with autocovariance r(k), k = 0 .. 2m - 1: the Allan
// difference (mean of the second m samples minus mean of the first m) has the weights -1 (m
// times) then +1 (m times) over m; their autocorrelation is 2m - 3k for k <= m and -(2m - k)
// for m < k < 2m.
template <typename Autocovariance>
double AvarFromAutocovariance(std::int64_t m, Autocovariance&& r) {
  long double sum = 2.0L * m * r(0);
  for (std::int64_t k = 1; k < 2 * m; ++k) {
    const long double w = k <= m ? 2.0L * m - 3.0L * k : -(2.0L * m - k);
    sum += 2.0L * w * r(k);
  }
  return static_cast<double>(sum / (2.0L * m * m));
}

long double FlickerAutocovariance(std::int64_t k) {
  long double r = 0.0L;
  for (int j = kFlickerFirst; j <= kFlickerLast; ++j) {
    r += std::exp(-static_cast<long double>(k) / FlickerCorrelationTime(j));
  }
  return r;
}

}  // namespace

const std::vector<PlainNoise>& PlainNoises() {
  static const std::vector<PlainNoise> kAll = {PlainNoise::kWhite, PlainNoise::kFlicker,
                                               PlainNoise::kRandomWalk,
                                               PlainNoise::kRandomWalkAveraged};
  return kAll;
}

std::string PlainNoiseLabel(PlainNoise noise) {
  switch (noise) {
    case PlainNoise::kWhite: return "white";
    case PlainNoise::kFlicker: return "flicker";
    case PlainNoise::kRandomWalk: return "random walk";
    case PlainNoise::kRandomWalkAveraged: return "random walk (averaged)";
    case PlainNoise::kQuantization: return "quantization";
  }
  return "?";
}

std::string PlainNoiseId(PlainNoise noise) {
  switch (noise) {
    case PlainNoise::kWhite: return "white";
    case PlainNoise::kFlicker: return "flicker";
    case PlainNoise::kRandomWalk: return "rw";
    case PlainNoise::kRandomWalkAveraged: return "rw_averaged";
    case PlainNoise::kQuantization: return "quantization";
  }
  return "?";
}

std::vector<double> GeneratePlain(PlainNoise noise, std::int64_t n, std::uint64_t seed,
                                  std::uint64_t stream) {
  if (n < 1) throw std::invalid_argument("plain noise: n must be >= 1");
  std::seed_seq seq{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32),
                    static_cast<std::uint32_t>(stream), static_cast<std::uint32_t>(stream >> 32),
                    static_cast<std::uint32_t>(noise)};
  std::mt19937_64 engine(seq);
  std::normal_distribution<double> normal;
  std::vector<double> y(static_cast<std::size_t>(n), 0.0);
  switch (noise) {
    case PlainNoise::kWhite:
      for (double& v : y) v = normal(engine);
      break;
    case PlainNoise::kRandomWalk: {
      double level = 0.0;
      for (double& v : y) v = level += normal(engine);
      break;
    }
    case PlainNoise::kRandomWalkAveraged: {
      // Over one unit interval a Wiener process moves dW ~ N(0, 1); its mean over the interval
      // is W_start + dW/2 + N(0, 1/12) independent of dW.
      double level = 0.0;
      const double bridge = std::sqrt(1.0 / 12.0);
      for (double& v : y) {
        const double step = normal(engine);
        v = level + 0.5 * step + bridge * normal(engine);
        level += step;
      }
      break;
    }
    case PlainNoise::kQuantization: {
      double previous = normal(engine);
      for (double& v : y) {
        const double theta = normal(engine);
        v = theta - previous;
        previous = theta;
      }
      break;
    }
    case PlainNoise::kFlicker:
      for (int j = kFlickerFirst; j <= kFlickerLast; ++j) {
        const double phi = std::exp(-1.0 / FlickerCorrelationTime(j));
        const double innovation = std::sqrt(1.0 - phi * phi);
        double x = normal(engine);  // stationary start
        for (double& v : y) {
          v += x;
          x = phi * x + innovation * normal(engine);
        }
      }
      break;
  }
  return y;
}

double PlainExpectedAvar(PlainNoise noise, std::int64_t m) {
  if (m < 1) throw std::invalid_argument("plain noise: m must be >= 1");
  const double md = static_cast<double>(m);
  switch (noise) {
    case PlainNoise::kWhite:
      return 1.0 / md;
    case PlainNoise::kRandomWalk:
      return (2.0 * md * md + 1.0) / (6.0 * md);
    case PlainNoise::kRandomWalkAveraged:
      return md / 3.0;
    case PlainNoise::kQuantization:
      return 3.0 / (md * md);
    case PlainNoise::kFlicker:
      return AvarFromAutocovariance(m, [](std::int64_t k) { return FlickerAutocovariance(k); });
  }
  return 0.0;
}

double PlainAutocovariance(PlainNoise noise, std::int64_t k) {
  if (k < 0) k = -k;
  switch (noise) {
    case PlainNoise::kWhite:
      return k == 0 ? 1.0 : 0.0;
    case PlainNoise::kQuantization:
      return k == 0 ? 2.0 : (k == 1 ? -1.0 : 0.0);
    case PlainNoise::kRandomWalk:
      return -0.5 * static_cast<double>(k);
    case PlainNoise::kFlicker:
      return static_cast<double>(FlickerAutocovariance(k));
    case PlainNoise::kRandomWalkAveraged:
      break;
  }
  throw std::invalid_argument("plain noise: no autocovariance for " + PlainNoiseLabel(noise));
}

}  // namespace allanlab::experiments
