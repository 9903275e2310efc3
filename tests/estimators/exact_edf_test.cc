// The exact EDF of (O)AVAR under a noise model reproduces the "exact" columns of docs/theory.md §3.2
// (three decimals printed, so the tolerance is half a unit of the last digit) and the white-noise
// closed form.
#include "estimators/exact_edf.h"

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>
#include <omp.h>

#include "tests/support/monte_carlo.h"

namespace allanlab::estimators {
namespace {

using sim::AvarEstimatorKind;
using testing_support::SingleTermModel;

struct Row {
  std::int64_t n, m;
  double overlapping, non_overlapping;
};

// EDF is scale-free, so unit coefficients at fs = 1 Hz stand for every record of that noise.
void ExpectTable(const sim::NoiseTerm& term, const std::vector<Row>& rows, double tolerance) {
  const sim::SensorModel model = SingleTermModel(term, 1.0);
  for (const Row& row : rows) {
    const std::int64_t ms[] = {row.m};
    const double ovl = ModelAvarEdf(model, ms, {row.n, AvarEstimatorKind::kOverlapping})[0];
    const double non = ModelAvarEdf(model, ms, {row.n, AvarEstimatorKind::kNonOverlapping})[0];
    EXPECT_NEAR(ovl, row.overlapping, tolerance)
        << sim::TermId(term) << " N=" << row.n << " m=" << row.m << " overlapping";
    EXPECT_NEAR(non, row.non_overlapping, tolerance)
        << sim::TermId(term) << " N=" << row.n << " m=" << row.m << " non-overlapping";
  }
}

TEST(ExactEdf, WhiteRateMatchesTheoryTable) {
  ExpectTable(sim::WhiteRateNoise{1.0},
              {{100, 1, 66.223, 66.223},
               {100, 10, 12.783, 6.231},
               {1000, 10, 146.072, 66.223},
               {1000, 100, 12.813, 6.231},
               {1000, 300, 3.157, 1.600}},
              5e-4);
}

TEST(ExactEdf, RandomWalkMatchesTheoryTable) {
  ExpectTable(sim::RandomWalkRate{1.0}, {{1000, 10, 91.755, 88.387}, {1000, 100, 7.757, 8.100}},
              5e-4);
  // Discrete random-walk differences at m = 1 are iid: EDF = N - 1 exactly (printed as 999.0).
  ExpectTable(sim::RandomWalkRate{1.0}, {{1000, 1, 999.0, 999.0}}, 1e-6);
}

TEST(ExactEdf, FlickerMatchesTheoryTable) {
  ExpectTable(sim::FlickerNoise{1.0}, {{1000, 10, 116.392, 87.167}, {1000, 100, 9.926, 8.074}},
              5e-4);
}

TEST(ExactEdf, QuantizationMatchesTheoryTable) {
  ExpectTable(sim::QuantizationNoise{1.0},
              {{1000, 10, 507.173, 51.180}, {1000, 100, 440.207, 4.909}}, 5e-4);
}

// docs/theory.md §3.2: non-overlapping white rate noise, M clusters: EDF = 2 (M - 1)^2 / (3M - 4).
TEST(ExactEdf, WhiteNonOverlappingClosedForm) {
  const sim::SensorModel model = SingleTermModel(sim::WhiteRateNoise{0.3}, 100.0);
  const std::vector<std::int64_t> ms = {1, 3, 7, 50, 333};
  const std::int64_t n = 1000;
  const std::vector<double> edf = ModelAvarEdf(model, ms, {n, AvarEstimatorKind::kNonOverlapping});
  for (std::size_t i = 0; i < ms.size(); ++i) {
    const double clusters = static_cast<double>(n / ms[i]);
    const double expected = 2.0 * (clusters - 1.0) * (clusters - 1.0) / (3.0 * clusters - 4.0);
    EXPECT_NEAR(edf[i], expected, 1e-9 * expected) << "m=" << ms[i];
  }
}

// The mean is the model's expected AVAR (both come from the same autocovariance), and averaging
// factors the record cannot hold give zero moments rather than garbage.
TEST(ExactEdf, MeanIsExpectedAvarAndInvalidFactorsAreZero) {
  const sim::SensorModel model = SingleTermModel(sim::WhiteRateNoise{0.3}, 100.0);
  const sim::RecordShape shape{1000, AvarEstimatorKind::kOverlapping};
  const std::vector<std::int64_t> ms = {0, 4, 501};
  const std::vector<AvarMoments> moments = ModelAvarMoments(model, ms, shape);
  EXPECT_EQ(moments[0].variance, 0.0);
  EXPECT_EQ(moments[2].edf(), 0.0);
  EXPECT_NEAR(moments[1].mean, model.ExpectedAvar(4, shape), 1e-12 * moments[1].mean);
}

// ModelAvarMoments shares one phase variogram across m: every m's moments are the bits of the
// per-m ExactAvarMoments (which builds its own), for both estimators and a long-memory term.
TEST(ExactEdf, SharedVariogramGivesThePerMBits) {
  for (const sim::NoiseTerm& term : {sim::NoiseTerm{sim::RandomWalkRate{0.01}}, sim::NoiseTerm{sim::WhiteRateNoise{0.3}}}) {
    const sim::SensorModel model = SingleTermModel(term, 100.0);
    for (AvarEstimatorKind kind : {AvarEstimatorKind::kOverlapping, AvarEstimatorKind::kNonOverlapping}) {
      const sim::RecordShape shape{3001, kind};
      const std::vector<std::int64_t> ms = {1, 2, 7, 100, 1000, 1500};
      const std::vector<AvarMoments> shared = ModelAvarMoments(model, ms, shape);
      const std::vector<double> r = model.GaussianAutocovariance(shape.num_samples + 2 * 1500);
      for (std::size_t i = 0; i < ms.size(); ++i) {
        const AvarMoments own = ExactAvarMoments(r, ms[i], shape);
        EXPECT_EQ(shared[i].mean, own.mean) << sim::TermId(term) << " m=" << ms[i];
        EXPECT_EQ(shared[i].variance, own.variance) << sim::TermId(term) << " m=" << ms[i];
      }
    }
  }
}

// The m are shared across threads: the same bits with one thread as with two.
TEST(ExactEdf, SameBitsForAnyThreadCount) {
  sim::SensorModel model = SingleTermModel(sim::RandomWalkRate{0.01}, 100.0);
  model.terms.push_back(sim::WhiteRateNoise{0.3});
  const sim::RecordShape shape{20000, AvarEstimatorKind::kOverlapping};
  const std::vector<std::int64_t> ms = {1, 3, 10, 33, 100, 333, 1000, 3333, 10000};
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const std::vector<AvarMoments> one = ModelAvarMoments(model, ms, shape);
  omp_set_num_threads(2);
  const std::vector<AvarMoments> two = ModelAvarMoments(model, ms, shape);
  omp_set_num_threads(threads);
  for (std::size_t i = 0; i < ms.size(); ++i) {
    EXPECT_EQ(one[i].mean, two[i].mean) << "m=" << ms[i];
    EXPECT_EQ(one[i].variance, two[i].variance) << "m=" << ms[i];
  }
}

}  // namespace
}  // namespace allanlab::estimators
