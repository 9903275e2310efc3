// The resonance candidate's start (resonance_estimate.h) on records from the independent generator
// (independent/: a point-sampled damped oscillator driven by white noise, its own discretization
// and random numbers): a broad, weak line is found where it is, and a record without one gives
// none.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "experiments/diagnosis/resonance_estimate.h"
#include "independent/generate.h"
#include "independent/recipe.h"
#include "tests/support/diagnosis_record.h"

namespace allanlab::experiments {
namespace {

constexpr double kRate = 100.0;
constexpr std::int64_t kSamples = 360000;  // 1 h

independent::Recipe Gyro() { return testing::IndependentMemsGyro(0.3, 3.0, 3.0); }

// Over 5 seeds from `seed_base`, the line is found within a quarter of its half-power width
// 2 zeta f0 of f0, and its damping within `damping_factor` of zeta.
void ExpectLineFound(const independent::Resonance& line, std::uint64_t seed_base, double damping_factor) {
  independent::Recipe r = Gyro();
  r.resonance = line;
  const double width_hz = 2.0 * line.damping_ratio * line.frequency_hz;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const std::vector<double> y = independent::Generate(r, kSamples, seed_base + seed, 0);
    std::string why;
    const auto est = EstimateResonance(y, 1.0 / kRate, &why);
    ASSERT_TRUE(est.has_value()) << "seed " << seed << ": " << why;
    EXPECT_NEAR(est->params.at("frequency_hz"), line.frequency_hz, 0.25 * width_hz) << "seed " << seed;
    EXPECT_GT(est->params.at("damping"), line.damping_ratio / damping_factor) << "seed " << seed;
    EXPECT_LT(est->params.at("damping"), line.damping_ratio * damping_factor) << "seed " << seed;
  }
}

// A line at 30.5 Hz with damping 0.107 (half-power width 2 zeta f0 = 6.5 Hz, as wide as the narrow
// search's +-64-bin floor window) whose peak stands ~15 % above the white floor (the independent
// benchmark's #52, unexplained because no line "rose 1.5x"). The Welch average of ~700 segments
// resolves it (~10 standard errors). The peak is found within a quarter of the line's width of f0
// over 5 seeds, and its damping within a factor 2 (a start: the fit polishes both).
TEST(ResonanceEstimateStatTest, FindsABroadWeakLine) {
  ExpectLineFound(independent::Resonance{1.5e-4, 30.5, 0.107}, 7100, 2.0);
}

// A broad line near Nyquist: 39.6 Hz, damping 0.09 (half-power width 7.1 Hz), its peak ~20 % above
// the white floor (as the independent benchmark's #22 of seed 4, 14 %, found by no search before: its
// flanks 64 bins (6.25 Hz) away still stood on the line). Found over 5 seeds, within a quarter
// of its width of f0 and its damping within a factor 2.5 (a start for the fit: the half-power
// points of so weak a line sit ~3 standard errors above the floor, and move with its noise).
TEST(ResonanceEstimateStatTest, FindsABroadLineNearNyquist) {
  ExpectLineFound(independent::Resonance{1.8e-4, 39.6, 0.09}, 7300, 2.5);
}

// No line: white noise, flicker and a random walk (a PSD falling as 1/f and 1/f^2 toward a flat
// floor), and the same band-limited by a second-order filter averaged to the output (a PSD that
// falls toward Nyquist, whose flat stretch stands above a median that takes in the roll-off).
// Neither is a line: no start over 20 seeds each.
TEST(ResonanceEstimateStatTest, NoLineInSlopesOrARollOff) {
  independent::Recipe plain = Gyro();
  independent::Recipe rolled = Gyro();
  rolled.low_pass = {independent::LowPassDesign::kSecondOrderBilinear, 30.0, 8, independent::Decimation::kAverage};
  for (const independent::Recipe* r : {&plain, &rolled}) {
    int found = 0;
    for (std::uint64_t seed = 1; seed <= 20; ++seed) {
      const std::vector<double> y = independent::Generate(*r, kSamples, 7200 + seed, 0);
      std::string why;
      if (const auto e = EstimateResonance(y, 1.0 / kRate, &why)) {
        ++found;
        ADD_FAILURE() << "seed " << seed << (r == &plain ? " plain" : " rolled off") << ": a line at "
                      << e->params.at("frequency_hz") << " Hz, damping " << e->params.at("damping");
      }
    }
    EXPECT_EQ(found, 0) << (r == &plain ? "plain" : "rolled off");
  }
}

}  // namespace
}  // namespace allanlab::experiments
