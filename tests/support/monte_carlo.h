#pragma once
// Monte Carlo checks of generators against exact theory (the statistical tier, docs/architecture.md "Conventions"). Tolerances come from
// the estimator's exact variance (docs/theory.md §3.1), never from guesses: the mean of `trials`
// independent AVAR estimates must lie within z * SD / sqrt(trials) of the exact expectation.
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sim/sensor_model.h"

namespace allanlab::testing_support {

// z = 5: a false failure in about 1 of 1.7 million comparisons (two-sided normal tail).
inline constexpr double kZ = 5.0;

struct AvarSample {
  std::vector<double> mean;      // per m: mean over trials of AVAR_hat
  std::vector<double> variance;  // per m: sample variance over trials
  int trials = 0;
};

// AVAR_hat at each m for trials 0..trials-1 of `model` under `seed` (records of n samples, drawn
// with `options`).
AvarSample SimulateAvar(const sim::SensorModel& model, std::uint64_t seed, int trials,
                        std::int64_t n, std::span<const std::int64_t> ms,
                        sim::AvarEstimatorKind kind, const sim::GenerateOptions& options = {});

// Exact SD of one AVAR estimate at each m for the model's Gaussian part (docs/theory.md §3.1).
std::vector<double> ExactAvarStdDev(const sim::SensorModel& model, std::int64_t n,
                                    std::span<const std::int64_t> ms, sim::AvarEstimatorKind kind);

// |mean_m - expected_m| <= z sd_m / sqrt(trials) at every m. The message lists m, expected,
// actual, tolerance and z-score for each m, failing or not.
::testing::AssertionResult MeanWithinTolerance(const AvarSample& sample,
                                               std::span<const double> expected,
                                               std::span<const double> sd_single,
                                               std::span<const std::int64_t> ms, double z = kZ);

// An output quantizer's exact theory against Monte Carlo: 200 records of 2^14 samples of `model`
// under `seed`, octave m up to N/8. `exact` compares the means with model.ExpectedAvar, the
// tolerance from the simulated spread (the quantization error is not Gaussian; z = 5);
// `white_worst_z` is the largest |z| of the same means against the unquantized model's AVAR plus
// `white_avar(m)`, the quantizer's white approximation: a test of the exact theory must also see
// the approximation fail, or it could not tell the two apart.
struct QuantizerTheoryCheck {
  ::testing::AssertionResult exact = ::testing::AssertionSuccess();
  double white_worst_z = 0.0;
};
QuantizerTheoryCheck CheckQuantizerTheory(const sim::SensorModel& model, const sim::SensorModel& unquantized,
                                          std::uint64_t seed, const std::function<double(std::int64_t m)>& white_avar);

// Octave averaging factors 1, 2, 4, ... <= n / 8.
std::vector<std::int64_t> OctaveFactorsUpTo(std::int64_t n_over);

// One-term models, without and with a band-limit.
sim::SensorModel SingleTermModel(const sim::NoiseTerm& term, double sample_rate_hz);

}  // namespace allanlab::testing_support
