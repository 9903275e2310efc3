// `diagnose --model N,B,K` names a warm-up drift and a random telegraph on records it was not built
// from (independent/: continuous-time terms averaged over each sample, its own random numbers),
// 2.5 h at 100 Hz on N 0.15 deg/sqrt(h), B 3 deg/h, K 3 deg/h/sqrt(h):
//   * a 60 deg/h warm-up drift settling with tw 600 s: named exponential_drift;
//   * a 4 deg/h random telegraph with a mean dwell of 60 s: named random_telegraph (its Allan
//     equivalent, the Gauss-Markov process, is told apart by the kurtosis of the block-mean
//     differences, docs/theory.md §6.6).
// A rate over fixed seeds, not one seed. Measured over seeds 100-109: the drift named 10 of 10
// (Wilson 95 % [72.2, 100] %); the telegraph named 6 of 10 ([31.3, 83.2] %: 2 named
// gauss_markov with the telegraph listed as equally consistent, 2 not flagged: at 4 deg/h and
// 60 s it is near the detection limit). The tests run seeds 100-105 (drift) and 100-107
// (telegraph) and ask for 5 of 6 (a rate of 90 % gives fewer with probability 0.11) and 3 of 8 (a
// rate of 60 % gives fewer with probability 0.05).
#include <gtest/gtest.h>

#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "experiments/diagnosis/diagnose.h"
#include "independent/generate.h"
#include "independent/recipe.h"
#include "tests/support/diagnosis_record.h"

namespace allanlab::experiments {
namespace {

constexpr double kDegPerHour = std::numbers::pi / 180.0 / 3600.0;
constexpr std::int64_t kSamples = 900000;  // 2.5 h at 100 Hz
constexpr int kFirstSeed = 100;

independent::Recipe Sensor() {
  independent::Recipe r;
  r.rate_hz = 100.0;
  r.noise.arw_rad_per_sqrt_s = 0.15 * std::numbers::pi / 180.0 / 60.0;
  r.noise.flicker_floor_rad_per_s = 0.6643 * 3.0 * kDegPerHour;  // recipe.h: the Allan floor
  r.noise.rrw_rad_per_s_per_sqrt_s = 3.0 * kDegPerHour / 60.0;
  return r;
}

// How many of the fixed seeds' records diagnose names `id` exactly.
int Named(const independent::Recipe& r, const std::string& id, int seeds) {
  int named = 0;
  for (int seed = kFirstSeed; seed < kFirstSeed + seeds; ++seed) {
    const DiagnosisSummary s = testing::DiagnoseIndependentRecord(r, kSamples, seed, testing::UserModelNBK());
    named += s.verdict == id;
    std::printf("seed %d: %s\n", seed, testing::DescribeVerdict(s).c_str());
  }
  return named;
}

TEST(DiagnoseWarmupTelegraph, WarmupDriftIsNamed) {
  independent::Recipe r = Sensor();
  r.warmup_drift = independent::WarmupDrift{60.0 * kDegPerHour, 600.0};
  EXPECT_GE(Named(r, "exponential_drift", 6), 5);
}

TEST(DiagnoseWarmupTelegraph, TelegraphIsNamed) {
  independent::Recipe r = Sensor();
  r.telegraph = independent::Telegraph{4.0 * kDegPerHour, 60.0};
  EXPECT_GE(Named(r, "random_telegraph", 8), 3);
}

}  // namespace
}  // namespace allanlab::experiments
