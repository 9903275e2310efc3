// An IIR band-limit section advanced per output period (sim/section_period.h), first-order and
// 2nd-order Butterworth: its held path against the internal-rate recursion (the same linear map:
// equal to rounding), and its records with white noise against the exact AVAR by Monte Carlo
// (z = 5 exact standard errors; the exact AVAR comes from the chain's impulse response,
// band_limited_avar.h, not from the per-period map).
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sim/sensor_model.h"
#include "tests/support/monte_carlo.h"

namespace allanlab::sim {
namespace {

namespace mc = testing_support;

constexpr GenerateOptions kPerPeriod{.white_per_output_period = true};

constexpr LowPassKind kSections[] = {LowPassKind::kFirstOrder, LowPassKind::kButterworth2};

SensorModel BandLimitedModel(std::vector<NoiseTerm> terms, LowPassKind kind, double cutoff_hz,
                             OutputSampling sampling) {
  SensorModel model;
  model.sample_clock = SampleClock::FromRateHz(100.0);
  model.terms = std::move(terms);
  model.band_limit = {kind, cutoff_hz, 8, sampling};
  return model;
}

std::string Describe(LowPassKind kind, double fc, OutputSampling sampling) {
  return std::string(kind == LowPassKind::kFirstOrder ? "first order" : "butterworth2") + " fc " +
         std::to_string(fc) + (sampling == OutputSampling::kAverage ? " averaged" : " point-sampled");
}

// Without white noise nothing is drawn per period: a random walk and a step (held terms, their own
// streams) come out of both routes alike.
TEST(SectionPeriod, HeldPathMatchesTheInternalRateRecursion) {
  for (LowPassKind kind : kSections) {
    for (OutputSampling sampling : {OutputSampling::kPoint, OutputSampling::kAverage}) {
      for (double fc : {36.0, 9.0, 0.5}) {
        const SensorModel model =
            BandLimitedModel({RandomWalkRate{0.01}, BiasStep{0.3, 12.345}}, kind, fc, sampling);
        std::string why;
        ASSERT_TRUE(model.IsValid(&why)) << why;
        const std::vector<double> internal = model.Generate(3, 1, 4000);
        const std::vector<double> per_period = model.Generate(3, 1, 4000, kPerPeriod);
        ASSERT_EQ(internal.size(), per_period.size());
        double scale = 0.0;
        for (double v : internal) scale = std::max(scale, std::abs(v));
        for (std::size_t k = 0; k < internal.size(); ++k) {
          // Rounding only: the two routes round differently, and a slow second-order section
          // (fc 0.5 Hz, poles 0.3 % from 1 at the internal rate) carries it over many periods (4e-13
          // of the scale seen).
          ASSERT_NEAR(per_period[k], internal[k], 1e-11 * scale) << Describe(kind, fc, sampling) << " sample " << k;
        }
      }
    }
  }
}

TEST(SectionPeriod, WhiteNoiseRecordsMatchTheExactAvar) {
  constexpr std::int64_t kSamples = 1 << 13;
  constexpr int kTrials = 150;
  for (LowPassKind kind : kSections) {
    for (OutputSampling sampling : {OutputSampling::kPoint, OutputSampling::kAverage}) {
      for (double fc : {58.0, 9.0}) {
        // White noise (drawn per period) and a Gauss-Markov term (held) through the filter.
        const SensorModel model =
            BandLimitedModel({WhiteRateNoise{0.01}, GaussMarkov{0.02, 0.03}}, kind, fc, sampling);
        const std::vector<std::int64_t> ms = mc::OctaveFactorsUpTo(kSamples / 8);
        const RecordShape shape{kSamples, AvarEstimatorKind::kOverlapping};
        const auto sample =
            mc::SimulateAvar(model, 20261127, kTrials, kSamples, ms, AvarEstimatorKind::kOverlapping, kPerPeriod);
        const std::vector<double> sd = mc::ExactAvarStdDev(model, kSamples, ms, AvarEstimatorKind::kOverlapping);
        EXPECT_TRUE(mc::MeanWithinTolerance(sample, model.ExpectedAvar(ms, shape), sd, ms))
            << Describe(kind, fc, sampling);
      }
    }
  }
}

// The per-period draws are the white noise's law, not a near miss: the same records scored against
// the other sampling's exact AVAR (averaged against point-sampled) fail.
TEST(SectionPeriod, TheCheckTellsTheSamplingsApart) {
  constexpr std::int64_t kSamples = 1 << 13;
  for (LowPassKind kind : kSections) {
    const SensorModel averaged = BandLimitedModel({WhiteRateNoise{0.01}}, kind, 58.0, OutputSampling::kAverage);
    const SensorModel point = BandLimitedModel({WhiteRateNoise{0.01}}, kind, 58.0, OutputSampling::kPoint);
    const std::vector<std::int64_t> ms = {1, 2, 4};
    const RecordShape shape{kSamples, AvarEstimatorKind::kOverlapping};
    const auto sample =
        mc::SimulateAvar(averaged, 20261127, 150, kSamples, ms, AvarEstimatorKind::kOverlapping, kPerPeriod);
    const std::vector<double> sd = mc::ExactAvarStdDev(point, kSamples, ms, AvarEstimatorKind::kOverlapping);
    EXPECT_FALSE(mc::MeanWithinTolerance(sample, point.ExpectedAvar(ms, shape), sd, ms))
        << Describe(kind, 58.0, OutputSampling::kAverage);
  }
}

}  // namespace
}  // namespace allanlab::sim
