// The R(n) window steps in AVX2 against the portable code, bit for bit: identification's choice
// between the phase noises and white FM must not depend on the CPU.
#include "estimators/ratio_window_steps.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

namespace allanlab::estimators {
namespace {

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(RatioWindowSteps, Avx2GivesThePortableBits) {
  if (!RatioStepsKernelRuns(RatioStepsKernel::kAvx2)) GTEST_SKIP() << "no AVX2";
  std::mt19937_64 rng(17);
  std::normal_distribution<double> normal;
  for (std::int64_t groups : {1, 2, 3, 50, 1024}) {
    // Four stretches of a random-walk phase (large level, small steps: the differences cancel
    // digits), and constant ones (every difference a zero, some of them negative zeros).
    for (int constant = 0; constant < 2; ++constant) {
      std::vector<double> x[4];
      for (std::vector<double>& v : x) {
        double level = 1e6 * normal(rng);
        for (std::int64_t i = 0; i < 4 * groups; ++i) v.push_back(constant ? -0.0 : (level += normal(rng)));
      }
      const double window = constant ? -0.0 : normal(rng);
      double s_portable[4] = {1, 2, 3, 4}, q_portable[4] = {5, 6, 7, 8};
      double s_vector[4] = {1, 2, 3, 4}, q_vector[4] = {5, 6, 7, 8};
      const double w_portable = RatioWindowSteps(x[0].data(), x[1].data(), x[2].data(), x[3].data(), groups, window,
                                                 s_portable, q_portable, RatioStepsKernel::kPortable);
      const double w_vector = RatioWindowSteps(x[0].data(), x[1].data(), x[2].data(), x[3].data(), groups, window,
                                               s_vector, q_vector, RatioStepsKernel::kAvx2);
      EXPECT_TRUE(SameBits(w_portable, w_vector)) << groups;
      for (int l = 0; l < 4; ++l) {
        EXPECT_TRUE(SameBits(s_portable[l], s_vector[l])) << "groups " << groups << " lane " << l;
        EXPECT_TRUE(SameBits(q_portable[l], q_vector[l])) << "groups " << groups << " lane " << l;
      }
    }
  }
}

}  // namespace
}  // namespace allanlab::estimators
