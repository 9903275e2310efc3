// A line's width at the record's full resolution (line_shape.h) on records from the independent
// generator (independent/: its own sinusoid and its own point-sampled damped oscillator): a
// sinusoid keeps its power in the periodogram's main lobe, a narrow resonance spreads it over its
// line width, even where the Allan variance and the Welch PSD see the same power at the same
// frequency for both (the independent benchmark's #83: an 8.64 Hz sinusoid named a resonance of
// damping 0.0027, line width 0.046 Hz, about 120 bins of the 1 h record's periodogram).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "experiments/diagnosis/line_shape.h"
#include "independent/generate.h"
#include "independent/recipe.h"
#include "tests/support/diagnosis_record.h"

namespace allanlab::experiments {
namespace {

constexpr double kRate = 100.0;
constexpr std::int64_t kSamples = 360000;  // 1 h; the periodogram takes 2^18 samples (3.8e-4 Hz bins)
constexpr double kF0 = 8.64;
constexpr double kDamping = 0.0027;
// Searched as the diagnosis does: over three of the resonance's line widths, from a frequency an
// Allan fit left 0.01 Hz (26 bins) off.
constexpr double kSearchHz = 3.0 * 2.0 * kDamping * kF0;
constexpr double kFittedHz = kF0 - 0.01;

independent::Recipe Gyro() { return testing::IndependentMemsGyro(0.3, 3.0, 3.0); }

// The sinusoid: 8e-5 rad/s (16.5 deg/h), random phase. The Hann lobe of +-2 bins holds all but
// ~1e-3 of its power: A^2 n / (4 sigma^2) ~ 550 times one bin's noise floor (sigma = 8.7e-4 rad/s
// per sample). The excess summed over the +-2W = 1470 bins carries noise of ~sqrt(1470) ~ 38
// floors, plus the floor's own error from its median (a few %: tens of floors), so the share is
// 550 / (550 +- ~50): above 0.75 (more than 4 of those deviations) on 5 of 5 seeds.
TEST(LineShapeStatTest, ASinusoidStaysInTheMainLobe) {
  independent::Recipe r = Gyro();
  r.sinusoid = independent::Sinusoid{8e-5, kF0, std::nullopt};
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const std::vector<double> y = independent::Generate(r, kSamples, 8300 + seed, 0);
    const double share = LineLobeShare(y, 1.0 / kRate, kFittedHz, kSearchHz);
    EXPECT_GT(share, 0.75) << "seed " << seed;
    EXPECT_GE(share, kSinusoidLobeShare) << "seed " << seed;
  }
}

// The resonance of the same power (sigma = A / sqrt(2)) and damping 0.0027: a Lorentzian of
// half-power half-width zeta f0 = 61 bins puts ~atan(2.5 / 61) / atan(2 W / 61) ~ 3 % of its power
// in the lobe (W = 3 line widths = 367 bins); below 0.2 on 5 of 5 seeds.
TEST(LineShapeStatTest, ANarrowResonanceSpreadsOverItsWidth) {
  independent::Recipe r = Gyro();
  r.resonance = independent::Resonance{8e-5 / std::sqrt(2.0), kF0, kDamping};
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const std::vector<double> y = independent::Generate(r, kSamples, 8400 + seed, 0);
    const double share = LineLobeShare(y, 1.0 / kRate, kFittedHz, kSearchHz);
    EXPECT_LT(share, 0.2) << "seed " << seed;
    EXPECT_LT(share, kSinusoidLobeShare) << "seed " << seed;
  }
}

}  // namespace
}  // namespace allanlab::experiments
