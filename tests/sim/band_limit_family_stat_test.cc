// The band-limit family (first and second order, impulse-invariant and bilinear, moving average
// and CIC; point-sampled or averaged; at the output rate or an internal rate): the exact AVAR of
// white noise behind each filter against an independent route, the autocovariance integrated
// from each filter's transfer function written here from its analog prototype (not from the
// coefficients or impulse response sim/ computes), and the generator against the exact AVAR by
// Monte Carlo (z = 5 exact standard errors).
#include <cmath>
#include <complex>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sim/band_limited_avar.h"
#include "tests/support/monte_carlo.h"

namespace allanlab::sim {
namespace {

using testing_support::ExactAvarStdDev;
using testing_support::MeanWithinTolerance;
using testing_support::OctaveFactorsUpTo;
using testing_support::SimulateAvar;
using cplx = std::complex<double>;

// x with (sin(pi x) / (pi x))^power = 1/sqrt(2), by Newton's method from 0.4.
double SincHalfPower(int power) {
  double x = 0.4;
  for (int i = 0; i < 60; ++i) {
    const double px = std::numbers::pi * x;
    const double s = std::sin(px) / px;
    const double ds = (std::cos(px) * px - std::sin(px)) / (px * x);
    const double f = std::pow(s, power) - 1.0 / std::numbers::sqrt2;
    const double df = power * std::pow(s, power - 1) * ds;
    x -= f / df;
  }
  return x;
}

// Frequency response at internal-rate angle w of each filter kind, from its definition.
cplx Response(LowPassKind kind, double fc, double fi, double w) {
  const cplx z1 = std::exp(cplx(0.0, -w));  // z^-1
  const double pi = std::numbers::pi;
  switch (kind) {
    case LowPassKind::kFirstOrder: {
      const double a = std::exp(-2.0 * pi * fc / fi);  // pole of the sampled RC response
      return (1.0 - a) / (1.0 - a * z1);
    }
    case LowPassKind::kFirstOrderBilinear:
    case LowPassKind::kButterworth2: {
      const double wc = 2.0 * fi * std::tan(pi * fc / fi);  // pre-warped
      const cplx s = 2.0 * fi * (1.0 - z1) / (1.0 + z1);
      if (kind == LowPassKind::kFirstOrderBilinear) return wc / (s + wc);
      return wc * wc / (s * s + std::numbers::sqrt2 * wc * s + wc * wc);
    }
    case LowPassKind::kButterworth2ImpulseInvariant: {
      // sum_n h(n T) z^-n, h(t) = sqrt(2) wc e^{-a t} sin(a t), as two geometric series, then
      // normalised to unit gain at DC.
      const double a = 2.0 * pi * fc / std::numbers::sqrt2 / fi;
      const cplx p = std::exp(cplx(-a, a));
      auto h = [&](cplx zinv) {
        return (1.0 / (1.0 - p * zinv) - 1.0 / (1.0 - std::conj(p) * zinv)) / cplx(0.0, 2.0);
      };
      return h(z1) / h(1.0);
    }
    case LowPassKind::kMovingAverage:
    case LowPassKind::kCic2: {
      const int stages = kind == LowPassKind::kMovingAverage ? 1 : 2;
      const double wlen = SincHalfPower(stages) * fi / fc;
      const auto whole = static_cast<int>(std::floor(wlen));
      // sum_{k < whole} z^-k = (1 - z^-whole) / (1 - z^-1), plus the fractional tap.
      const cplx zw = std::exp(cplx(0.0, -w * whole));
      cplx box = w == 0.0 ? cplx(whole) : (1.0 - zw) / (1.0 - z1);
      box += (wlen - whole) * zw;
      box /= wlen;
      return stages == 1 ? box : box * box;
    }
    case LowPassKind::kNone: return 1.0;
  }
  return 1.0;
}

// Output autocovariance at lags 0..lags-1 (output samples) of internal white noise of variance v
// through the filter (and the mean of L internal samples when averaged), decimated by L:
//   R(j) = v / (2 pi) int_{-pi}^{pi} |G(w)|^2 cos(w j L) dw, by Simpson's rule on [0, pi].
std::vector<double> IntegratedAcov(const BandLimit& b, double fs, double v, std::int64_t lags) {
  const double fi = fs * b.oversampling;
  const int n = 1 << 16;
  const double h = std::numbers::pi / n;
  std::vector<long double> s(static_cast<std::size_t>(lags), 0.0L);
  for (int i = 0; i <= n; ++i) {
    const double w = i * h;
    cplx g = Response(b.kind, b.cutoff_hz, fi, w);
    if (b.sampling == OutputSampling::kAverage && b.oversampling > 1) {
      cplx box = 0.0;
      for (int k = 0; k < b.oversampling; ++k) box += std::exp(cplx(0.0, -w * k));
      g *= box / static_cast<double>(b.oversampling);
    }
    const double weight = (i == 0 || i == n ? 1.0 : (i % 2 ? 4.0 : 2.0)) * std::norm(g);
    for (std::int64_t j = 0; j < lags; ++j) {
      s[static_cast<std::size_t>(j)] += weight * std::cos(w * static_cast<double>(j * b.oversampling));
    }
  }
  std::vector<double> r;
  for (long double x : s) r.push_back(static_cast<double>(v * x * h / 3.0 / std::numbers::pi));
  return r;
}

struct FamilyCase {
  std::string name;
  BandLimit limit;
};
std::ostream& operator<<(std::ostream& os, const FamilyCase& c) { return os << c.name; }

std::vector<FamilyCase> Cases() {
  std::vector<FamilyCase> cases;
  for (const BandLimitFamily& f : BandLimitFamilies()) {
    // A cutoff near the ADIS16405's (a box of ~1.2 output periods) and a slower one.
    for (double fc : {36.0, 9.0}) {
      cases.push_back({std::string(f.name) + "_" + std::to_string(static_cast<int>(fc)) + "Hz",
                       BandLimit{f.kind, fc, f.oversampling, f.sampling}});
    }
  }
  return cases;
}

class BandLimitFamilyTest : public ::testing::TestWithParam<FamilyCase> {};

TEST_P(BandLimitFamilyTest, WhiteNoiseAvarMatchesTransferFunctionIntegral) {
  const FamilyCase& c = GetParam();
  const double fs = 100.0, arw = 0.01;
  SensorModel model;
  model.sample_clock = SampleClock::FromRateHz(fs);
  model.terms = {WhiteRateNoise{arw}};
  model.band_limit = c.limit;
  std::string why;
  ASSERT_TRUE(model.IsValid(&why)) << why;
  // White rate noise of density N enters at the internal rate with variance N^2 / tau_internal.
  const double v = arw * arw * fs * c.limit.oversampling;
  const std::int64_t max_m = 16;
  const std::vector<double> acov = IntegratedAcov(c.limit, fs, v, 2 * max_m + 4);
  const std::vector<std::int64_t> ms = {1, 2, 3, 5, 8, 16};
  const RecordShape shape{1 << 16, AvarEstimatorKind::kOverlapping};
  const std::vector<double> exact = model.ExpectedAvar(ms, shape);
  const std::vector<double> fast = model.ExpectedAvar(ms, shape, FlickerBandLimit::kStationaryChange);
  for (std::size_t k = 0; k < ms.size(); ++k) {
    // Brute-force Allan quadratic form over the integrated autocovariance.
    const std::int64_t m = ms[k];
    long double s = 0.0L;
    for (std::int64_t i = 0; i < 2 * m; ++i) {
      for (std::int64_t j = 0; j < 2 * m; ++j) {
        s += (i < m ? -1.0 : 1.0) * (j < m ? -1.0 : 1.0) * acov[static_cast<std::size_t>(std::abs(i - j))];
      }
    }
    const double route = static_cast<double>(s / (2.0L * m * m));
    EXPECT_NEAR(exact[k], route, 1e-6 * route) << c.name << " m " << m;
    EXPECT_NEAR(fast[k], route, 1e-6 * route) << c.name << " m " << m;
  }
}

TEST_P(BandLimitFamilyTest, MonteCarloMatchesExactAvar) {
  const FamilyCase& c = GetParam();
  constexpr std::int64_t kSamples = 1 << 13;
  constexpr int kTrials = 150;
  SensorModel model;
  model.sample_clock = SampleClock::FromRateHz(100.0);
  // White noise (wideband path) and a Gauss-Markov term (held path) through the filter.
  model.terms = {WhiteRateNoise{0.01}, GaussMarkov{0.02, 0.03}};
  model.band_limit = c.limit;
  const std::vector<std::int64_t> ms = OctaveFactorsUpTo(kSamples / 8);
  const RecordShape shape{kSamples, AvarEstimatorKind::kOverlapping};
  const auto sample = SimulateAvar(model, 20261124, kTrials, kSamples, ms, AvarEstimatorKind::kOverlapping);
  const std::vector<double> sd = ExactAvarStdDev(model, kSamples, ms, AvarEstimatorKind::kOverlapping);
  EXPECT_TRUE(MeanWithinTolerance(sample, model.ExpectedAvar(ms, shape), sd, ms)) << c.name;
}

INSTANTIATE_TEST_SUITE_P(Families, BandLimitFamilyTest, ::testing::ValuesIn(Cases()),
                         [](const auto& info) { return info.param.name; });

// A moving average 1.205 output periods long (fc = 0.4429 / 1.205 fs) correlates adjacent
// outputs of white noise by (w - 1) / w = 0.17 and no further ones: the short correlation of the
// ADIS16405's X and Y axes (lag-1 0.170 and 0.171, lag-2 below 0.005 over 1e6 samples each).
TEST(BandLimitFamily, MovingAverageGivesTheLagOneCorrelationOfAnInternalDecimator) {
  const double fs = 100.0;
  SensorModel model;
  model.sample_clock = SampleClock::FromRateHz(fs);
  model.terms = {WhiteRateNoise{0.01}};
  model.band_limit = {LowPassKind::kMovingAverage, SincHalfPower(1) * fs / 1.205, 8, OutputSampling::kPoint};
  const std::vector<double> r = model.GaussianAutocovariance(4);
  // The box of 9.64 internal samples shares 1.64 of them with the next output: 0.174.
  EXPECT_NEAR(r[1] / r[0], 0.205 / 1.205, 0.006);
  EXPECT_NEAR(r[2] / r[0], 0.0, 1e-12);
  // A first-order low-pass with the same lag-1 correlation would leave lag 2 at ~0.17^2: the two
  // are told apart by the record.
  model.band_limit = {LowPassKind::kFirstOrder, 1.0, 8, OutputSampling::kPoint};
  double lo = 1.0, hi = 400.0;
  for (int i = 0; i < 60; ++i) {
    model.band_limit.cutoff_hz = std::sqrt(lo * hi);
    const std::vector<double> q = model.GaussianAutocovariance(3);
    (q[1] / q[0] > 0.17 ? lo : hi) = model.band_limit.cutoff_hz;
  }
  const std::vector<double> q = model.GaussianAutocovariance(3);
  EXPECT_GT(q[2] / q[0], 0.02);
}

TEST(BandLimitFamily, RefusesABoxShorterThanAnInternalSample) {
  BandLimit b{LowPassKind::kMovingAverage, 390.0, 2, OutputSampling::kPoint};
  std::string why;
  EXPECT_FALSE(b.IsValid(100.0, &why));
  EXPECT_NE(why.find("shorter than one internal sample"), std::string::npos) << why;
  b.cutoff_hz = 80.0;
  EXPECT_TRUE(b.IsValid(100.0, &why)) << why;
}

}  // namespace
}  // namespace allanlab::sim
