// BiasStep::ExpectedAvar's memo (no band-limit) gives back the bits of a fresh computation, on
// the first call and on later ones, and keeps steps of other sizes, times and shapes apart.
#include <cstdint>

#include <gtest/gtest.h>

#include "sim/bias_step.h"

namespace allanlab::sim {
namespace {

TEST(BiasStepMemo, MemoisedValuesAreTheFreshBits) {
  const double tau0 = 0.01;
  for (const BiasStep step : {BiasStep{3e-6, 41.27}, BiasStep{-3e-6, 41.27}, BiasStep{3e-6, 500.0}}) {
    for (std::int64_t n : {100001, 50000}) {
      for (AvarEstimatorKind kind : {AvarEstimatorKind::kOverlapping, AvarEstimatorKind::kNonOverlapping}) {
        const RecordShape shape{n, kind};
        for (int pass = 0; pass < 2; ++pass) {
          for (std::int64_t m : {1, 7, 100, 4000, 20000}) {
            EXPECT_EQ(step.ExpectedAvar(m, tau0, shape), step.ExpectedAvarUncached(m, tau0, shape))
                << "b " << step.size_rad_per_s << " t " << step.time_s << " n " << n << " m " << m;
          }
        }
      }
    }
  }
}

}  // namespace
}  // namespace allanlab::sim
