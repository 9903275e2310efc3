// The narrowband resonance (damped oscillator driven by white noise): its exact AVAR against a
// brute-force Allan quadratic form over the oscillator's textbook autocovariance, its continuous
// AVAR against the numerical integral of the oscillator's PSD, and the generator's records
// against the exact AVAR by Monte Carlo (tolerance from the estimator's exact variance, z = 5).
#include "sim/resonance.h"

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/monte_carlo.h"

namespace allanlab::sim {
namespace {

using testing_support::ExactAvarStdDev;
using testing_support::MeanWithinTolerance;
using testing_support::OctaveFactorsUpTo;
using testing_support::SimulateAvar;

// R(t) = sigma^2 e^{-a t} (cos(wd t) + (a / wd) sin(wd t)), a = zeta w0, wd = w0 sqrt(1 - zeta^2):
// the underdamped oscillator's autocovariance (e.g. Papoulis), written here apart from sim/.
double OscillatorAcov(double sigma, double f0, double zeta, double t) {
  const double w0 = 2.0 * std::numbers::pi * f0;
  const double a = zeta * w0, wd = w0 * std::sqrt(1.0 - zeta * zeta);
  t = std::abs(t);
  return sigma * sigma * std::exp(-a * t) * (std::cos(wd * t) + a / wd * std::sin(wd * t));
}

// AVAR(m) = E[(mean of block 2 - mean of block 1)^2] / 2 as the double sum over the 2m samples'
// weights -1/m, +1/m: O(m^2), no lag weights.
double BruteForceAvar(std::int64_t m, const std::function<double(std::int64_t)>& acov) {
  long double s = 0.0L;
  for (std::int64_t i = 0; i < 2 * m; ++i) {
    for (std::int64_t j = 0; j < 2 * m; ++j) {
      const double wi = i < m ? -1.0 : 1.0, wj = j < m ? -1.0 : 1.0;
      s += wi * wj * acov(i - j);
    }
  }
  return static_cast<double>(s / (2.0L * m * m));
}

struct Case {
  double sigma, f0, zeta, fs;
};

TEST(ResonanceTest, ExactAvarMatchesBruteForceQuadraticForm) {
  // A 20 Hz line at 100 Hz (ADIS16405 Z), one above Nyquist (aliased), one slow and lightly
  // damped (the closed form's near-cancellation branch at small m |1 - z|).
  for (const Case c : {Case{0.01, 20.0, 0.04, 100.0}, Case{0.02, 71.0, 0.2, 100.0},
                       Case{0.003, 0.02, 0.01, 100.0}, Case{1.0, 3.0, 0.7, 50.0}}) {
    const Resonance r{c.sigma, c.f0, c.zeta};
    const double tau0 = 1.0 / c.fs;
    for (std::int64_t m : {1, 2, 3, 7, 16, 64, 200, 256}) {
      const double brute =
          BruteForceAvar(m, [&](std::int64_t k) { return OscillatorAcov(c.sigma, c.f0, c.zeta, k * tau0); });
      const double exact = r.ExpectedAvar(m, tau0, RecordShape{1 << 20});
      EXPECT_NEAR(exact, brute, 1e-9 * std::abs(brute) + 1e-14 * c.sigma * c.sigma)
          << "f0 " << c.f0 << " zeta " << c.zeta << " m " << m;
    }
    std::vector<double> acov(5);
    r.FillAutocovariance(tau0, acov, 3);
    for (int k = 0; k < 5; ++k) {
      EXPECT_NEAR(acov[static_cast<std::size_t>(k)], OscillatorAcov(c.sigma, c.f0, c.zeta, (3 + k) * tau0),
                  1e-12 * c.sigma * c.sigma);
    }
  }
}

// One-sided PSD of the oscillator in Hz: var = int_0^inf S df, from |H(w)|^2 =
// 1 / ((w0^2 - w^2)^2 + (2 zeta w0 w)^2) and Var = q / (4 zeta w0^3) for white input density q.
double OscillatorPsd(double sigma, double f0, double zeta, double f) {
  const double w0 = 2.0 * std::numbers::pi * f0, w = 2.0 * std::numbers::pi * f;
  const double q = 4.0 * zeta * w0 * w0 * w0 * sigma * sigma;
  const double h2 = 1.0 / ((w0 * w0 - w * w) * (w0 * w0 - w * w) + 4.0 * zeta * zeta * w0 * w0 * w * w);
  return 2.0 * 2.0 * std::numbers::pi * q * h2 / (2.0 * std::numbers::pi);  // 2 S_two-sided(w) dw/df / 2pi
}

TEST(ResonanceTest, ContinuousAvarMatchesIntegralOfPsd) {
  const double sigma = 0.01, f0 = 20.0, zeta = 0.05;
  const Resonance r{sigma, f0, zeta};
  // The PSD integrates to sigma^2 (checks the PSD's normalisation first).
  auto integrate = [&](const std::function<double(double)>& g) {
    // Simpson on [0, 400 f0] with a fine step through the line; the tail beyond falls as f^-4.
    const int n = 2000000;
    const double hi = 400.0 * f0, h = hi / n;
    long double s = g(0.0) + g(hi);
    for (int i = 1; i < n; ++i) s += (i % 2 ? 4.0 : 2.0) * g(i * h);
    return static_cast<double>(s * h / 3.0);
  };
  EXPECT_NEAR(integrate([&](double f) { return OscillatorPsd(sigma, f0, zeta, f); }), sigma * sigma,
              1e-5 * sigma * sigma);
  for (double tau : {0.005, 0.02, 0.05, 0.31, 1.0, 10.0}) {
    // AVAR(tau) = 2 int S(f) sin^4(pi f tau) / (pi f tau)^2 df.
    const double avar = integrate([&](double f) {
      if (f == 0.0) return 0.0;
      const double x = std::numbers::pi * f * tau, s = std::sin(x);
      return 2.0 * OscillatorPsd(sigma, f0, zeta, f) * s * s * s * s / (x * x);
    });
    EXPECT_NEAR(r.AsymptoticAvar(tau), avar, 2e-4 * avar) << "tau " << tau;
  }
}

TEST(ResonanceTest, MonteCarloMatchesExactAvarAlsoBehindABandLimit) {
  constexpr std::int64_t kSamples = 1 << 14;
  constexpr int kTrials = 200;
  for (LowPassKind kind : {LowPassKind::kNone, LowPassKind::kMovingAverage, LowPassKind::kButterworth2}) {
    SensorModel model;
    model.sample_clock = SampleClock::FromRateHz(100.0);
    model.terms = {WhiteRateNoise{0.002}, Resonance{0.02, 20.0, 0.04}};
    model.band_limit = {kind, 40.0, 4, OutputSampling::kPoint};
    std::string why;
    ASSERT_TRUE(model.IsValid(&why)) << why;
    const std::vector<std::int64_t> ms = OctaveFactorsUpTo(kSamples / 8);
    const RecordShape shape{kSamples, AvarEstimatorKind::kOverlapping};
    const auto sample = SimulateAvar(model, 20261124, kTrials, kSamples, ms, AvarEstimatorKind::kOverlapping);
    const std::vector<double> sd = ExactAvarStdDev(model, kSamples, ms, AvarEstimatorKind::kOverlapping);
    EXPECT_TRUE(MeanWithinTolerance(sample, model.ExpectedAvar(ms, shape), sd, ms)) << LowPassKindName(kind);
  }
}

TEST(ResonanceTest, RejectsDampingOutsideTheUnderdampedRange) {
  std::string why;
  EXPECT_FALSE((Resonance{0.01, 20.0, 0.0}.IsValid(&why)));
  EXPECT_NE(why.find("damping"), std::string::npos);
  EXPECT_FALSE((Resonance{0.01, 20.0, 1.0}.IsValid(&why)));
  EXPECT_FALSE((Resonance{0.01, -1.0, 0.1}.IsValid(&why)));
  EXPECT_TRUE((Resonance{0.01, 20.0, 0.5}.IsValid(&why)));
}

}  // namespace
}  // namespace allanlab::sim
