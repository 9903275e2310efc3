// Outliers with heavy-tailed (exponential) magnitudes and one-sided spikes: the exact AVAR
// against the per-sample variance written here from the laws (p E[a^2] - (p E[signed a])^2, over
// m), and the generator against it by Monte Carlo (the spikes are far from Gaussian: the
// tolerance is z = 5 of the simulated spread), plus the record's sample moments.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sim/sensor_spec.h"
#include "tests/support/monte_carlo.h"

namespace allanlab::sim {
namespace {

using testing_support::MeanWithinTolerance;
using testing_support::OctaveFactorsUpTo;
using testing_support::SimulateAvar;

struct LawCase {
  SpikeSign sign;
  SpikeSize law;
  double second_moment;  // E[a^2] / a^2
  double mean_sign;      // E[signed a] / a
};

TEST(OutliersLawsTest, ExactAvarMatchesTheLawsAndMonteCarlo) {
  constexpr double kRate = 100.0, p = 0.02, a = 0.05;
  constexpr std::int64_t kSamples = 1 << 13;
  const LawCase cases[] = {{SpikeSign::kSymmetric, SpikeSize::kFixed, 1.0, 0.0},
                           {SpikeSign::kSymmetric, SpikeSize::kExponential, 2.0, 0.0},
                           {SpikeSign::kPositive, SpikeSize::kExponential, 2.0, 1.0},
                           {SpikeSign::kNegative, SpikeSize::kFixed, 1.0, -1.0}};
  for (const LawCase& c : cases) {
    Outliers o{p * kRate, a, c.sign, c.law};
    const double var = p * c.second_moment * a * a - (p * c.mean_sign * a) * (p * c.mean_sign * a);
    for (std::int64_t m : {1, 4, 100}) {
      EXPECT_NEAR(o.ExpectedAvar(m, 1.0 / kRate, RecordShape{kSamples}), var / static_cast<double>(m), 1e-15);
    }
    SensorModel model;
    model.sample_clock = SampleClock::FromRateHz(kRate);
    model.terms = {WhiteRateNoise{1e-3}, o};
    const std::vector<std::int64_t> ms = OctaveFactorsUpTo(kSamples / 8);
    const RecordShape shape{kSamples, AvarEstimatorKind::kOverlapping};
    const auto sample = SimulateAvar(model, 20261124, 300, kSamples, ms, AvarEstimatorKind::kOverlapping);
    std::vector<double> sd;
    for (double v : sample.variance) sd.push_back(std::sqrt(v));
    EXPECT_TRUE(MeanWithinTolerance(sample, model.ExpectedAvar(ms, shape), sd, ms));
    // The record's mean and the share of samples beyond 5 a (none for fixed spikes; e^-5 of the
    // spikes for exponential ones): sample moments with z = 5 binomial / normal tolerances.
    SensorModel spikes_only;
    spikes_only.sample_clock = SampleClock::FromRateHz(kRate);
    spikes_only.terms = {o};
    const std::vector<double> y = spikes_only.Generate(7, 0, 1 << 20);
    double mean = 0.0;
    std::int64_t beyond = 0;
    for (double v : y) {
      mean += v;
      beyond += std::abs(v) > 5.0 * a;
    }
    const double n = static_cast<double>(y.size());
    mean /= n;
    EXPECT_NEAR(mean, p * c.mean_sign * a, 5.0 * std::sqrt(var / n));
    const double q = c.law == SpikeSize::kExponential ? p * std::exp(-5.0) : 0.0;
    EXPECT_NEAR(static_cast<double>(beyond) / n, q, 5.0 * std::sqrt(q * (1.0 - q) / n) + 1e-12);
  }
}

TEST(OutliersLawsTest, SpecReadsTheSignAndLaw) {
  SensorModel model;
  std::string why;
  ASSERT_TRUE(LoadSensorModelYaml(R"(name: spiky
sample_rate: 100 Hz
terms:
  - {type: outliers, rate: 0.1 Hz, size: 1 deg/s, sign: positive, size_law: exponential}
)", "test", &model, &why)) << why;
  const auto& o = std::get<Outliers>(model.terms[0]);
  EXPECT_EQ(o.sign, SpikeSign::kPositive);
  EXPECT_EQ(o.size_law, SpikeSize::kExponential);
  EXPECT_FALSE(LoadSensorModelYaml(R"(name: spiky
sample_rate: 100 Hz
terms:
  - {type: outliers, rate: 0.1 Hz, size: 1 deg/s, sign: sideways}
)", "test", &model, &why));
  EXPECT_NE(why.find("sideways"), std::string::npos) << why;
}

}  // namespace
}  // namespace allanlab::sim
