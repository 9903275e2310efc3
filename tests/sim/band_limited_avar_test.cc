// The fast band-limited AVAR (sim/band_limited_avar.h) against the direct quadratic form: the
// chain's output autocovariance over all 2m lags (BandLimitChain::WhiteOutputAutocovariance /
// HeldOutputAutocovariance) summed with the Allan lag weights, for several filters, rates,
// oversamplings, output samplings and averaging factors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "sim/avar_theory.h"
#include "sim/band_limited_avar.h"
#include "sim/sensor_model.h"
#include "sim/units.h"

namespace allanlab::sim {
namespace {

struct ChainCase {
  LowPassKind kind;
  double fc_hz;
  int oversampling;
  OutputSampling sampling;
};

std::vector<ChainCase> Cases() {
  std::vector<ChainCase> cases;
  for (LowPassKind kind : {LowPassKind::kFirstOrder, LowPassKind::kButterworth2}) {
    for (double fc : {12.0, 100.0, 170.0}) {
      for (int l : {1, 3, 8}) {
        for (OutputSampling s : {OutputSampling::kPoint, OutputSampling::kAverage}) {
          if (fc < 0.45 * l * 400.0) cases.push_back({kind, fc, l, s});
        }
      }
    }
  }
  return cases;
}

constexpr double kRate = 400.0;
const std::int64_t kMs[] = {1, 2, 3, 5, 8, 17, 60, 333, 4000};
const RecordShape kShape{1 << 14, AvarEstimatorKind::kOverlapping};

// Direct sum for a held term with autocovariance from FillAutocovariance.
template <typename T>
double DirectHeld(const T& t, const BandLimitChain& chain, std::int64_t m) {
  std::vector<double> r_in(static_cast<std::size_t>(2 * m) + chain.held_response().size());
  t.FillAutocovariance(1.0 / kRate, r_in);
  return AvarFromAutocovariance(m, chain.HeldOutputAutocovariance(r_in, 2 * m));
}

template <typename T>
void ExpectHeldMatches(const T& t, double tolerance) {
  for (const ChainCase& c : Cases()) {
    const BandLimitChain chain(BandLimit{c.kind, c.fc_hz, c.oversampling, c.sampling}, kRate);
    std::vector<double> change;
    ASSERT_TRUE(BandLimitAvarChange(t, chain, 1.0 / kRate, kMs, &change));
    for (std::size_t k = 0; k < std::size(kMs); ++k) {
      const std::int64_t m = kMs[k];
      const double own = t.ExpectedAvar(m, 1.0 / kRate, kShape);
      const double direct = DirectHeld(t, chain, m);
      EXPECT_NEAR((own + change[k]) / direct, 1.0, tolerance)
          << T::kId << " fc " << c.fc_hz << " L " << c.oversampling << " kind "
          << static_cast<int>(c.kind) << " sampling " << static_cast<int>(c.sampling) << " m " << m;
    }
  }
}

TEST(BandLimitedAvarTest, WhiteNoiseMatchesTheDirectSum) {
  const WhiteRateNoise t{units::DegPerSqrtHour(0.0267)};
  for (const ChainCase& c : Cases()) {
    const BandLimitChain chain(BandLimit{c.kind, c.fc_hz, c.oversampling, c.sampling}, kRate);
    std::vector<double> change;
    ASSERT_TRUE(BandLimitAvarChange(t, chain, 1.0 / kRate, kMs, &change));
    const double internal_var = t.arw_rad_per_sqrt_s * t.arw_rad_per_sqrt_s / chain.internal_period_s();
    for (std::size_t k = 0; k < std::size(kMs); ++k) {
      const std::int64_t m = kMs[k];
      const double direct = AvarFromAutocovariance(m, chain.WhiteOutputAutocovariance(internal_var, 2 * m));
      const double fast = t.ExpectedAvar(m, 1.0 / kRate, kShape) + change[k];
      EXPECT_NEAR(fast / direct, 1.0, 1e-12) << "fc " << c.fc_hz << " L " << c.oversampling << " m " << m;
    }
  }
}

TEST(BandLimitedAvarTest, RandomWalkMatchesTheDirectSum) {
  ExpectHeldMatches(RandomWalkRate{units::DegPerHourPerSqrtHour(0.03)}, 1e-11);
}

TEST(BandLimitedAvarTest, GaussMarkovAndTelegraphMatchTheDirectSum) {
  ExpectHeldMatches(GaussMarkov{units::DegPerHour(5.0), 0.02}, 1e-11);
  ExpectHeldMatches(RandomTelegraph{units::DegPerHour(3.0), 0.5}, 1e-11);
  // Correlation far longer than the record (phi -> 1: the closed-form window sum of long lags
  // must not cancel) and far shorter than a sample.
  ExpectHeldMatches(GaussMarkov{units::DegPerHour(5.0), 1e4}, 1e-11);
  ExpectHeldMatches(RandomTelegraph{units::DegPerHour(3.0), 1e-4}, 1e-11);
}

TEST(BandLimitedAvarTest, ResonanceMatchesTheDirectSum) {
  // A line near 20 Hz (the ADIS16405 Z axis), a slow, lightly damped mode (pole near 1: the
  // window sums must not cancel) and a broad one near the output Nyquist frequency. Agreement
  // to 1.4e-8 at worst (the broad mode at m = 17), 1e-10 at most taus.
  ExpectHeldMatches(Resonance{units::DegPerHour(1200.0), 20.5, 0.022}, 5e-8);
  ExpectHeldMatches(Resonance{units::DegPerHour(5.0), 0.05, 0.01}, 5e-8);
  ExpectHeldMatches(Resonance{units::DegPerHour(50.0), 190.0, 0.4}, 5e-8);
}

TEST(BandLimitedAvarTest, StationaryFlickerMatchesTheDirectSum) {
  // Against the direct sum of the stationary-increment (generalised) autocovariance.
  const FlickerNoise t{units::DegPerHour(0.18)};
  for (const ChainCase& c : Cases()) {
    const BandLimitChain chain(BandLimit{c.kind, c.fc_hz, c.oversampling, c.sampling}, kRate);
    std::vector<double> change;
    ASSERT_TRUE(BandLimitAvarChange(t, chain, 1.0 / kRate, kMs, &change));
    for (std::size_t k = 0; k < std::size(kMs); ++k) {
      const std::int64_t m = kMs[k];
      const double direct = DirectHeld(t, chain, m);
      const double fast = t.StationaryAvar(m) + change[k];
      EXPECT_NEAR(fast / direct, 1.0, 1e-11) << "fc " << c.fc_hz << " L " << c.oversampling << " m " << m;
    }
  }
}

TEST(BandLimitedAvarTest, SensorModelMatchesTheDirectSumOfItsTerms) {
  // SensorModel::ExpectedAvar against an independent route: quantization (after the filter) and
  // the ramp (filter-invariant) by their own closed forms, white noise and the random walk by the
  // direct quadratic form over the chain's output autocovariance.
  const QuantizationNoise quantization{1e-7};
  const WhiteRateNoise white{units::DegPerSqrtHour(0.0267)};
  const RandomWalkRate walk{units::DegPerHourPerSqrtHour(0.03)};
  const RateRamp ramp{units::DegPerHourSquared(5.0)};
  SensorModel model;
  model.sample_clock = SampleClock::FromRateHz(kRate);
  model.terms = {quantization, white, walk, ramp};
  const double tau0 = 1.0 / kRate;
  for (const ChainCase& c : Cases()) {
    model.band_limit = BandLimit{c.kind, c.fc_hz, c.oversampling, c.sampling};
    const BandLimitChain chain(model.band_limit, kRate);
    const double internal_var = white.arw_rad_per_sqrt_s * white.arw_rad_per_sqrt_s / chain.internal_period_s();
    const std::vector<double> model_avar = model.ExpectedAvar(kMs, kShape);
    for (std::size_t k = 0; k < std::size(kMs); ++k) {
      const std::int64_t m = kMs[k];
      const double direct = quantization.ExpectedAvar(m, tau0, kShape) +
                            AvarFromAutocovariance(m, chain.WhiteOutputAutocovariance(internal_var, 2 * m)) +
                            DirectHeld(walk, chain, m) + ramp.ExpectedAvar(m, tau0, kShape);
      EXPECT_NEAR(model_avar[k] / direct, 1.0, 1e-11) << "fc " << c.fc_hz << " L " << c.oversampling << " m " << m;
    }
  }
}

TEST(BandLimitedAvarTest, KasdinFlickerDiffersByAStartUpTermOnly) {
  // SensorModel starts Kasdin flicker from a zero state at the first sample; the fast path adds
  // the stationary-increment change. The difference is a start-up effect shared by the T Allan
  // differences, of the order of the filter memory over T: |fast/slow - 1| < 0.5 (tc + 1)/T
  // (tc = fs/(2 pi fc) samples; measured up to 0.43 (tc + 1)/T here, and scaling as 1/N for
  // N = 2^12..2^18 at fixed m).
  SensorModel model;
  model.sample_clock = SampleClock::FromRateHz(kRate);
  model.terms = {FlickerNoise{units::DegPerHour(0.18)}};
  for (const ChainCase& c : Cases()) {
    model.band_limit = BandLimit{c.kind, c.fc_hz, c.oversampling, c.sampling};
    const std::vector<double> fast = model.ExpectedAvar(kMs, kShape, FlickerBandLimit::kStationaryChange);
    const std::vector<double> slow = model.ExpectedAvar(kMs, kShape, FlickerBandLimit::kExact);
    const double tc = kRate / (2.0 * std::numbers::pi * c.fc_hz);
    for (std::size_t k = 0; k < std::size(kMs); ++k) {
      const double t = static_cast<double>(kShape.num_samples - 2 * kMs[k] + 1);
      EXPECT_NEAR(fast[k] / slow[k], 1.0, 0.5 * (tc + 1.0) / t) << "fc " << c.fc_hz << " L " << c.oversampling << " m " << kMs[k];
    }
  }
}

TEST(BandLimitedAvarTest, HarmonicHasNoFastForm) {
  const BandLimitChain chain(BandLimit{LowPassKind::kFirstOrder, 100.0, 8, OutputSampling::kPoint}, kRate);
  std::vector<double> change = {42.0};
  EXPECT_FALSE(BandLimitAvarChange(Harmonic{1e-5, 3.0, std::nullopt}, chain, 1.0 / kRate, kMs, &change));
  EXPECT_EQ(change.size(), 1u);
}

}  // namespace
}  // namespace allanlab::sim
