// BoxFilter::FilterInPlace is Step run over a span: the same outputs, bit for bit, whatever the
// split of the input into spans (the simulator filters an oversampled record chunk by chunk).
#include <cstddef>
#include <vector>

#include <boost/random/normal_distribution.hpp>
#include <gtest/gtest.h>

#include "sim/band_limit.h"
#include "sim/seeding.h"

namespace allanlab::sim {
namespace {

TEST(BoxFilter, FilterInPlaceMatchesStepBitForBit) {
  Engine engine = MakeEngine(11, 0, 0);
  boost::random::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> x(10000);
  for (double& v : x) v = 3.0 + normal(engine);  // an offset: the running sum's rounding matters
  for (double w : {1.0, 2.5, 7.0, 18.0867, 181.3}) {
    BoxFilter stepped(w), spans(w);
    std::vector<double> expected(x.size()), got = x;
    for (std::size_t i = 0; i < x.size(); ++i) expected[i] = stepped.Step(x[i]);
    // Uneven pieces, as chunks of an oversampled record.
    std::size_t start = 0;
    for (std::size_t piece = 1; start < got.size(); piece = piece * 3 + 1) {
      const std::size_t len = std::min(piece, got.size() - start);
      spans.FilterInPlace(std::span<double>(got).subspan(start, len));
      start += len;
    }
    for (std::size_t i = 0; i < x.size(); ++i) {
      ASSERT_EQ(got[i], expected[i]) << "w " << w << " sample " << i;
    }
  }
}

}  // namespace
}  // namespace allanlab::sim
