// The z of the halves view (gap.h ZFromLogRatioEnvelope): ln(OAVAR_first / OAVAR_second) at 2
// EDF per half is ln F(2, 2), the standard logistic distribution (sd pi / sqrt(3)), whose tail
// P(X > x) = 1 / (1 + e^x) is known in closed form.
#include <gtest/gtest.h>

#include <cmath>

#include <boost/math/distributions/normal.hpp>

#include "experiments/diagnosis/gap.h"

namespace allanlab::experiments {
namespace {

TEST(DiagnosisGapTest, HalvesZUsesTheLogFTailsAtFewDegreesOfFreedom) {
  const double sd = M_PI / std::sqrt(3.0);
  const int trials = 100000;  // the prediction inflation sqrt(1 + 1/trials) is then negligible
  const double x = 4.0 * sd;
  const double tail = 1.0 / (1.0 + std::exp(x));
  const double expected = -boost::math::quantile(boost::math::normal(), tail);  // ~3.19
  EXPECT_NEAR(ZFromLogRatioEnvelope(0.5 + x, 0.5, sd, trials), expected, 0.02);
  EXPECT_NEAR(ZFromLogRatioEnvelope(0.5 - x, 0.5, sd, trials), -expected, 0.02);
  // The normal reading of the same point (4 sd) overstates it.
  EXPECT_GT(ZFromEnvelope(0.5 + x, 0.5, sd, trials), expected + 0.5);
}

TEST(DiagnosisGapTest, HalvesZIsNormalAtManyDegreesOfFreedom) {
  // nu = 2000: ln F has sd ~ sqrt(4 / nu) and is nearly normal.
  const double sd = std::sqrt(4.0 / 2000.0);
  EXPECT_NEAR(ZFromLogRatioEnvelope(3.0 * sd, 0.0, sd, 100000), 3.0, 0.1);
  EXPECT_TRUE(std::isnan(ZFromLogRatioEnvelope(1.0, 0.0, 0.0, 30)));
}

}  // namespace
}  // namespace allanlab::experiments
