// Tier a, end to end: ComputeAvar on the OCXO record (19982 fractional-frequency samples, tau0 =
// 1 s; tests/data/reference/ocxo/SOURCE.txt) against Stable32 1.60's octave tables: terms, the
// identified noise exponent and the interval widths. This record, unlike PHASE.DAT, has every
// noise type from flicker PM to random-walk FM, so it exercises each EDF branch.
//
// What is compared and why:
// * Interval widths as ratios MinSigma/Sigma and MaxSigma/Sigma, with Stable32's alpha forced
//   per row: the octave tables were made from a differently prepared copy of the data (their
//   header reports an average of 1.000000) and their deviations differ from Stable32's own
//   all-tau tables (which allanlab matches) by up to 2e-3, while the ratios depend only on EDF and
//   confidence. Tolerance: two 5-digit roundings plus the small-EDF quantile drift (see
//   stable32_phasedat_ref_test.cc).
// * Deviations loosely (2e-3), except TOTDEV: Stable32 applies the SP 1065 TOTVAR bias
//   correction 1 / (1 - a tau/T) (a = 0.481 FFM, 0.750 RWFM), which explains its 0.3-1.2 %
//   larger values at m >= 256; allanlab reports the uncorrected estimator.
// * Identified alpha: every row with at least 30 m-averages (the lag-1 ACF regime) must agree.
//   Below that (B1 ratio, 4-19 averages) Stable32's rule is not documented well enough to
//   reproduce: its ADEV and OADEV tables even disagree with each other at the same m; the rows
//   listed in kKnownAlphaDifferences differ (and are printed), the rest agree.
#include <cmath>
#include <cstdio>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "estimators/avar.h"
#include "tests/support/stable32_table.h"

namespace allanlab::estimators {
namespace {

using testing_support::ReadDataColumn;
using testing_support::ReadStable32Table;
using testing_support::Stable32Interval;
using testing_support::MatchesStable32Interval;
using testing_support::NearRelative;
using testing_support::Stable32Row;

const std::string kDir = std::string(ALLANLAB_TEST_DATA_DIR) + "/reference/ocxo/";

const std::vector<double>& FractionalFrequency() {
  static const std::vector<double> y = [] {
    std::vector<double> f = ReadDataColumn(kDir + "ocxo_frequency.txt");
    for (double& v : f) v = v / 1e7 - 1.0;
    return f;
  }();
  return y;
}

const std::set<std::pair<std::string, std::int64_t>> kKnownAlphaDifferences = {
    {"adev", 1024},  {"adev", 2048},  {"oadev", 2048},  {"oadev", 4096},  {"mdev", 2048},
    {"mdev", 4096},  {"tdev", 2048},  {"tdev", 4096},   {"hdev", 1024},   {"hdev", 2048},
    {"ohdev", 2048}, {"ohdev", 4096}, {"totdev", 2048}, {"totdev", 4096}, {"totdev", 8192}};

AvarOptions OcxoOptions(Statistic statistic, std::vector<double> taus) {
  AvarOptions options;
  options.confidence_method = ConfidenceMethod::kGreenhallRiley;  // Stable32's method
  options.statistic = statistic;
  options.input = InputKind::kRate;
  options.taus.kind = TauGridKind::kExplicit;
  options.taus.explicit_taus_s = std::move(taus);
  return options;
}

void ExpectTableMatches(Statistic statistic, const std::string& name) {
  const std::vector<Stable32Row> rows = ReadStable32Table(kDir + name + "_octave.txt");
  const std::vector<double>& y = FractionalFrequency();
  ASSERT_EQ(y.size(), 19982u);
  std::vector<double> taus;
  for (const Stable32Row& r : rows) taus.push_back(r.tau_s);
  AvarSummary identified;
  ASSERT_TRUE(ComputeAvar(OcxoOptions(statistic, taus), y, &identified)) << identified.message;
  ASSERT_EQ(identified.points.size(), rows.size());

  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Stable32Row& r = rows[i];
    const AvarPoint& p = identified.points[i];
    SCOPED_TRACE(name + " m=" + std::to_string(r.m));
    EXPECT_EQ(p.terms, r.terms);
    if (statistic != Statistic::kTotal) {
      EXPECT_TRUE(NearRelative("sigma", std::sqrt(p.value), r.sigma, 2e-3));
    }
    if (kKnownAlphaDifferences.count({name, r.m}) == 0) {
      EXPECT_EQ(p.alpha, r.alpha) << "averages: " << y.size() / r.m;
    } else if (p.alpha != r.alpha) {
      std::printf("known difference: %s m=%lld alpha %d, Stable32 %d (%zu averages)\n",
                  name.c_str(), static_cast<long long>(r.m), p.alpha, r.alpha, y.size() / r.m);
    }

    AvarOptions forced = OcxoOptions(statistic, {r.tau_s});
    forced.alpha_fixed = true;
    forced.alpha = r.alpha;
    AvarSummary one;
    ASSERT_TRUE(ComputeAvar(forced, y, &one)) << one.message;
    const AvarPoint& q = one.points.at(0);
    const Interval s32 = Stable32Interval(q.value, q.edf);
    const double sigma = std::sqrt(q.value);
    const double tol = 2e-4 + 2e-3 / q.edf;
    SCOPED_TRACE("alpha=" + std::to_string(r.alpha) + " edf=" + std::to_string(q.edf));
    EXPECT_TRUE(NearRelative("min/sigma", std::sqrt(s32.low) / sigma, r.min_sigma / r.sigma, tol));
    EXPECT_TRUE(NearRelative("max/sigma", std::sqrt(s32.high) / sigma, r.max_sigma / r.sigma, tol));
  }
}

TEST(Stable32Ocxo, AllanNonOverlapping) {
  ExpectTableMatches(Statistic::kAllanNonOverlapping, "adev");
}
TEST(Stable32Ocxo, AllanOverlapping) { ExpectTableMatches(Statistic::kAllanOverlapping, "oadev"); }
TEST(Stable32Ocxo, ModifiedAllan) { ExpectTableMatches(Statistic::kModifiedAllan, "mdev"); }
TEST(Stable32Ocxo, Time) { ExpectTableMatches(Statistic::kTime, "tdev"); }
TEST(Stable32Ocxo, HadamardNonOverlapping) {
  ExpectTableMatches(Statistic::kHadamardNonOverlapping, "hdev");
}
TEST(Stable32Ocxo, HadamardOverlapping) {
  ExpectTableMatches(Statistic::kHadamardOverlapping, "ohdev");
}
TEST(Stable32Ocxo, Total) { ExpectTableMatches(Statistic::kTotal, "totdev"); }

}  // namespace
}  // namespace allanlab::estimators
