// The z of the halves view (gap.h ZFromLogRatioEnvelope): ln(OAVAR_first / OAVAR_second) at 2
// EDF per half is ln F(2, 2), the standard logistic distribution (sd pi / sqrt(3)), whose tail
// P(X > x) = 1 / (1 + e^x) is known in closed form. The z of a log-variance view
// (ZFromLogVarianceEnvelope) at 2 EDF: chi2_2 / 2 is Exp(1), so ln of it has mean -gamma, sd
// pi / sqrt(6) and lower tail P(X < x) = 1 - exp(-e^x).
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

TEST(DiagnosisGapTest, LogVarianceZUsesTheChiSquareLowerTailAtFewDegreesOfFreedom) {
  const double euler_gamma = 0.5772156649015329;
  const double sd = M_PI / std::sqrt(6.0);
  const int trials = 100000;
  const double mean = 1.0;  // the envelope's centre: ln E + E ln(chi2_2 / 2), any E
  // A record whose chi2_2 / 2 is 2.5e-4: the exact lower tail 2.5e-4, z = -3.48.
  const double x = std::log(2.5e-4);
  const double observed = mean + euler_gamma + x;
  const double expected = boost::math::quantile(boost::math::normal(), -std::expm1(-std::exp(x)));
  EXPECT_NEAR(ZFromLogVarianceEnvelope(observed, mean, sd, trials), expected, 0.02);
  // The normal reading puts the same record at z ~ -6: a false alarm at any Bonferroni level.
  EXPECT_LT(ZFromEnvelope(observed, mean, sd, trials), expected - 2.0);
  // Above the model the chi-square tail is lighter than the normal's, and the smaller |z| (the
  // Student reading) is kept.
  EXPECT_DOUBLE_EQ(ZFromLogVarianceEnvelope(mean + 3.0 * sd, mean, sd, trials),
                   ZFromEnvelope(mean + 3.0 * sd, mean, sd, trials));
}

TEST(DiagnosisGapTest, LogVarianceZIsNormalAtManyDegreesOfFreedom) {
  const double sd = std::sqrt(2.0 / 5000.0);  // ln chi2_nu / nu at nu = 5000
  EXPECT_NEAR(ZFromLogVarianceEnvelope(-3.0 * sd, 0.0, sd, 100000), -3.0, 0.1);
  EXPECT_TRUE(std::isnan(ZFromLogVarianceEnvelope(1.0, 0.0, 0.0, 30)));
}

// From an envelope of 30 records, the Student reading (t on 29 degrees of freedom) protects a
// point near a threshold against the envelope sd's own uncertainty; far beyond every threshold it
// only compresses the departure, and there the law's reading is kept (gap.cc SmallerInMagnitude),
// the scale a view read from theory has.
TEST(DiagnosisGapTest, AFarDepartureFromAnEnvelopeReadsOnTheLawsScale) {
  const double sd = std::sqrt(2.0 / 5000.0);  // ln chi2_nu / nu at nu = 5000: nearly normal
  const int trials = 30;
  // 4.5 sd above (t = 4.43, Student z 3.9): the Student reading, the smaller.
  EXPECT_DOUBLE_EQ(ZFromLogVarianceEnvelope(4.5 * sd, 0.0, sd, trials), ZFromEnvelope(4.5 * sd, 0.0, sd, trials));
  EXPECT_LT(ZFromEnvelope(4.5 * sd, 0.0, sd, trials), 4.0);
  // 12 sd above (t = 11.8, Student z about 7): the law's reading, about 11.8.
  const double student = ZFromEnvelope(12.0 * sd, 0.0, sd, trials);
  EXPECT_GT(student, 6.0);
  EXPECT_LT(student, 8.0);
  EXPECT_NEAR(ZFromLogVarianceEnvelope(12.0 * sd, 0.0, sd, trials), 12.0 / std::sqrt(1.0 + 1.0 / trials), 0.5);
}

}  // namespace
}  // namespace allanlab::experiments
