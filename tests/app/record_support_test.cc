// The record-length rule: P fitted parameters need P + 1 octave taus with at least 8 clusters,
// and a term that dominates only above T/8 is named.
#include "app/input/record_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace allanlab::app {
namespace {

TEST(RecordSupportTest, OctaveCountFollowsTheClusterRule) {
  EXPECT_EQ(SupportedOctaveTaus(7), 0);
  EXPECT_EQ(SupportedOctaveTaus(8), 1);     // m = 1
  EXPECT_EQ(SupportedOctaveTaus(100), 4);   // m = 1, 2, 4, 8 <= 12
  EXPECT_EQ(SupportedOctaveTaus(255), 5);   // m <= 31
  EXPECT_EQ(SupportedOctaveTaus(256), 6);   // m <= 32
}

TEST(RecordSupportTest, ShortRecordsCannotCarryManyParameters) {
  std::string why;
  EXPECT_TRUE(CheckRecordSupportsFit(256, 100, 5, &why));
  EXPECT_TRUE(CheckRecordSupportsFit(16, 100, 1, &why));
  EXPECT_FALSE(CheckRecordSupportsFit(255, 100, 5, &why));
  ASSERT_FALSE(CheckRecordSupportsFit(100, 100, 5, &why));
  EXPECT_EQ(why, "1 s (100 samples at 100 Hz) gives 4 octave tau(s) with at least 8 clusters "
                 "(tau <= T/8); fitting 5 parameter(s) needs 6: record at least 2.56 s (256 "
                 "samples), or fit fewer terms (--terms)");
}

// White noise N^2/tau and a rate ramp R^2 tau^2/2 (IEEE 952 shapes, written here in closed form):
// R is named when it overtakes N only above T/8, not when it does well below.
TEST(RecordSupportTest, TermDominatingOnlyAboveTheSupportedTausIsNamed) {
  const std::int64_t samples = 1 << 12;
  const double tau0 = 0.01;
  std::vector<double> tau;
  std::vector<std::int64_t> m;
  for (std::int64_t k = 1; k <= samples / 2; k *= 2) {
    m.push_back(k);
    tau.push_back(k * tau0);
  }
  const auto terms = [&](double crossing_tau) {
    // R^2 c^2 / 2 = N^2 / c at the crossing c.
    const double n2 = 1e-6, r2 = 2.0 * n2 / std::pow(crossing_tau, 3);
    FittedTermAvar n{"N", {}}, r{"R", {}};
    for (double t : tau) {
      n.avar.push_back(n2 / t);
      r.avar.push_back(r2 * t * t / 2.0);
    }
    return std::vector<FittedTermAvar>{n, r};
  };
  const double t_over_8 = samples / 8 * tau0;  // 5.12 s
  const std::vector<std::string> late = WeaklySupportedTerms(tau, m, samples, terms(2 * t_over_8));
  ASSERT_EQ(late.size(), 1u);
  EXPECT_EQ(late[0].rfind("R exceeds half of the fitted curve only from tau 20.5 s, above T/8 = "
                          "5.12 s where fewer than 8 clusters average", 0),
            0u)
      << late[0];
  EXPECT_TRUE(WeaklySupportedTerms(tau, m, samples, terms(t_over_8 / 4)).empty());
}

}  // namespace
}  // namespace allanlab::app
