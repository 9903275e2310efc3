// The one-pass octave estimator agrees with the in-memory one (estimators/allan_variance.h) to
// 1e-9 relative where it claims to be exact, computes exactly the strided estimator it documents
// above exact_overlap_max_m, and keeps its state bounded.
#include "estimators/streaming_avar.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <span>
#include <utility>
#include <vector>

#include "estimators/allan_variance.h"

namespace allanlab::estimators {
namespace {

// White + random-walk rate with a bias 1e4 times the white level and a ramp: the digits the
// prefix sums must not lose.
std::vector<double> Record(std::int64_t n, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  std::normal_distribution<double> normal;
  std::vector<double> y(static_cast<std::size_t>(n));
  double walk = 0;
  for (std::int64_t k = 0; k < n; ++k) {
    walk += 1e-3 * normal(engine);
    y[static_cast<std::size_t>(k)] = 1e4 + 2e-6 * static_cast<double>(k) + normal(engine) + walk;
  }
  return y;
}

StreamingAvar Stream(const std::vector<double>& y, std::int64_t exact_max_m) {
  StreamingAvar s(StreamingAvarOptions{exact_max_m});
  for (double v : y) s.Add(v);
  return s;
}

void ExpectRelativeNear(double actual, double expected, double tolerance, const char* what,
                        std::int64_t m) {
  EXPECT_LE(std::abs(actual - expected), tolerance * std::abs(expected))
      << what << " at m = " << m << ": expected " << expected << ", actual " << actual
      << ", relative tolerance " << tolerance;
}

TEST(StreamingAvarTest, AgreesWithInMemoryEstimatorsTo1e9) {
  const std::int64_t n = 200003;  // not a power of two: partial last clusters
  const std::vector<double> y = Record(n, 42);
  const StreamingAvar s = Stream(y, std::int64_t{1} << 17);
  const std::vector<StreamingAvarPoint> points = s.Points();
  std::vector<std::int64_t> ms;
  for (const StreamingAvarPoint& p : points) ms.push_back(p.m);
  ASSERT_EQ(ms, OctaveAveragingFactors(n / 2));
  const std::vector<double> overlapping = AllanVariance(y, ms, AvarEstimatorKind::kOverlapping);
  const std::vector<double> plain = AllanVariance(y, ms, AvarEstimatorKind::kNonOverlapping);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const StreamingAvarPoint& p = points[i];
    EXPECT_EQ(p.overlapping_stride, 1);
    EXPECT_EQ(p.overlapping_terms, n - 2 * p.m + 1);
    EXPECT_EQ(p.nonoverlapping_terms, n / p.m - 1);
    ExpectRelativeNear(p.overlapping, overlapping[i], 1e-9, "overlapping", p.m);
    ExpectRelativeNear(p.nonoverlapping, plain[i], 1e-9, "non-overlapping", p.m);
  }
}

TEST(StreamingAvarTest, DefaultIsExactUpToItsLimit) {
  const std::int64_t n = 70001;
  const std::vector<double> y = Record(n, 7);
  const StreamingAvar s = Stream(y, StreamingAvarOptions().exact_overlap_max_m);
  std::vector<std::int64_t> ms;
  for (const StreamingAvarPoint& p : s.Points()) {
    if (p.overlapping_stride == 1) ms.push_back(p.m);
  }
  ASSERT_EQ(ms.back(), StreamingAvarOptions().exact_overlap_max_m);
  const std::vector<double> overlapping = AllanVariance(y, ms, AvarEstimatorKind::kOverlapping);
  for (std::size_t i = 0; i < ms.size(); ++i) {
    ExpectRelativeNear(s.Points()[i].overlapping, overlapping[i], 1e-9, "overlapping", ms[i]);
  }
}

// The first sample, which the stream subtracts from every other, lies 1e6 noise levels from the
// rest: the prefix sums reach ~2e11 while their second differences are ~1, so a plain double
// running sum would keep ~5 of their digits (u |S| ~ 4e-5); hi + lo must keep them to 1e-9.
TEST(StreamingAvarTest, AFarFirstSampleCostsNoDigits) {
  const std::int64_t n = 200000;
  std::mt19937_64 engine(11);
  std::normal_distribution<double> normal;
  std::vector<double> y(static_cast<std::size_t>(n));
  for (double& v : y) v = normal(engine);
  y[0] = 1e6;
  const StreamingAvar s = Stream(y, std::int64_t{1} << 17);
  std::vector<std::int64_t> ms;
  for (const StreamingAvarPoint& p : s.Points()) ms.push_back(p.m);
  const std::vector<double> overlapping = AllanVariance(y, ms, AvarEstimatorKind::kOverlapping);
  const std::vector<double> plain = AllanVariance(y, ms, AvarEstimatorKind::kNonOverlapping);
  for (std::size_t i = 0; i < ms.size(); ++i) {
    ExpectRelativeNear(s.Points()[i].overlapping, overlapping[i], 1e-9, "overlapping", ms[i]);
    ExpectRelativeNear(s.Points()[i].nonoverlapping, plain[i], 1e-9, "non-overlapping", ms[i]);
  }
}

// Above exact_overlap_max_m the starts are every s = m / exact_overlap_max_m samples: checked
// against a direct sum over exactly those starts. The second record spans ~15 of the blocks in
// which the estimator folds its prefix sums (2 exact_overlap_max_m + 1 + 2048 values), so every
// octave's terms cross block boundaries.
TEST(StreamingAvarTest, StridedStartsAboveTheExactLimit) {
  for (const auto& [n, exact_max_m] : {std::pair<std::int64_t, std::int64_t>{5000, 4}, {30011, 8}}) {
    const std::vector<double> y = Record(n, 3);
    StreamingAvar s(StreamingAvarOptions{exact_max_m});
    s.Add(std::span<const double>(y).first(1000));
    for (std::size_t k = 1000; k < y.size(); ++k) s.Add(y[k]);
    std::vector<long double> prefix(y.size() + 1, 0.0L);
    for (std::size_t k = 0; k < y.size(); ++k) prefix[k + 1] = prefix[k] + (y[k] - y[0]);
    const std::vector<StreamingAvarPoint> points = s.Points();
    EXPECT_EQ(points.size(), static_cast<std::size_t>(std::bit_width(static_cast<std::uint64_t>(n / 2))));
    for (const StreamingAvarPoint& p : points) {
      const std::int64_t stride = std::max<std::int64_t>(1, p.m / exact_max_m);
      EXPECT_EQ(p.overlapping_stride, stride);
      long double sum = 0;
      std::int64_t terms = 0;
      for (std::int64_t t = 0; t + 2 * p.m <= n; t += stride) {
        const long double d = prefix[t + 2 * p.m] - 2 * prefix[t + p.m] + prefix[t];
        sum += d * d;
        ++terms;
      }
      EXPECT_EQ(p.overlapping_terms, terms) << "n = " << n << ", m = " << p.m;
      const double expected = static_cast<double>(sum / (2.0L * p.m * p.m * terms));
      ExpectRelativeNear(p.overlapping, expected, 1e-9, "strided overlapping", p.m);
    }
  }
}

TEST(StreamingAvarTest, StateIsBoundedByTheOctaveCount) {
  const std::int64_t exact_max_m = 256;
  StreamingAvar s(StreamingAvarOptions{exact_max_m});
  std::mt19937_64 engine(1);
  std::normal_distribution<double> normal;
  std::size_t bytes_at_1e5 = 0;
  for (std::int64_t k = 1; k <= 2000000; ++k) {
    s.Add(normal(engine));
    if (k == 100000) bytes_at_1e5 = s.StateBytes();
  }
  // 20x the samples adds log2(20) < 5 octaves of at most (2 * 256 + 1) 16-byte entries each.
  const std::size_t per_octave = (2 * exact_max_m + 1) * 16 + 256;
  EXPECT_LE(s.StateBytes() - bytes_at_1e5, 5 * per_octave)
      << "state grew from " << bytes_at_1e5 << " to " << s.StateBytes() << " bytes";
  // Plus the prefix-sum buffer (2 * 256 + 1 kept and room for kRoomBlocks blocks of 2048, high and
  // low parts) and the 2048 samples gathered for the next block while the current one is folded.
  const std::size_t buffers = (2 * (2 * exact_max_m + 1 + StreamingAvar::kRoomBlocks * 2048) + 2048) * 8;
  EXPECT_LE(s.StateBytes(), 23 * per_octave + buffers);
}

TEST(StreamingAvarTest, FewSamplesAndInvalidOptions) {
  StreamingAvar s;
  s.Add(1.0);
  EXPECT_TRUE(s.Points().empty());
  s.Add(3.0);
  ASSERT_EQ(s.Points().size(), 1u);
  EXPECT_EQ(s.Points()[0].overlapping, 2.0);  // (3 - 1)^2 / 2
  std::string why;
  EXPECT_FALSE(StreamingAvarOptions{3}.IsValid(&why));
  EXPECT_EQ(why, "exact_overlap_max_m must be a power of two >= 1, got 3");
  EXPECT_FALSE(StreamingAvarOptions{0}.IsValid(&why));
}

// Blocks folded by two threads, one thread, in spans of any length or a value at a time: the
// same bits (the octaves' sums do not depend on who computed them, FastTwoSum's errors are
// TwoSum's), checked against the one-value-at-a-time run with OpenMP limited to one thread.
TEST(StreamingAvarTest, ThreadsAndSpansNeverChangeTheBits) {
  const std::vector<double> y = Record(300000, 11);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const std::vector<StreamingAvarPoint> one = Stream(y, 4096).Points();
  omp_set_num_threads(std::max(threads, 2));
  StreamingAvar spans(StreamingAvarOptions{4096});  // blocks of 8192: shared
  for (std::size_t i = 0; i < y.size(); i += 4099) {
    spans.Add(std::span<const double>(y).subspan(i, std::min<std::size_t>(4099, y.size() - i)));
  }
  omp_set_num_threads(threads);
  const std::vector<StreamingAvarPoint> two = spans.Points();
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t k = 0; k < one.size(); ++k) {
    EXPECT_EQ(std::bit_cast<std::uint64_t>(one[k].overlapping), std::bit_cast<std::uint64_t>(two[k].overlapping)) << one[k].m;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(one[k].nonoverlapping), std::bit_cast<std::uint64_t>(two[k].nonoverlapping)) << one[k].m;
    EXPECT_EQ(one[k].overlapping_terms, two[k].overlapping_terms);
    EXPECT_EQ(one[k].nonoverlapping_terms, two[k].nonoverlapping_terms);
  }
}

// Spans that hold whole blocks (a raw reader's chunks) are taken where they lie, not gathered:
// spans of exactly a block, of several blocks and a part, and a mix, give the one-thread bits.
TEST(StreamingAvarTest, BlocksTakenFromTheCallersSpanKeepTheBits) {
  const std::vector<double> y = Record(150001, 19);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const std::vector<StreamingAvarPoint> one = Stream(y, 1024).Points();  // blocks of 2048
  omp_set_num_threads(std::max(threads, 2));
  for (std::size_t span : {std::size_t{2048}, std::size_t{7000}, std::size_t{4096 + 1}}) {
    StreamingAvar s(StreamingAvarOptions{1024});
    for (std::size_t i = 0; i < y.size(); i += span) {
      s.Add(std::span<const double>(y).subspan(i, std::min(span, y.size() - i)));
    }
    const std::vector<StreamingAvarPoint> two = s.Points();
    ASSERT_EQ(one.size(), two.size());
    for (std::size_t k = 0; k < one.size(); ++k) {
      EXPECT_EQ(std::bit_cast<std::uint64_t>(one[k].overlapping), std::bit_cast<std::uint64_t>(two[k].overlapping))
          << "span " << span << ", m = " << one[k].m;
      EXPECT_EQ(std::bit_cast<std::uint64_t>(one[k].nonoverlapping), std::bit_cast<std::uint64_t>(two[k].nonoverlapping))
          << "span " << span << ", m = " << one[k].m;
    }
  }
  omp_set_num_threads(threads);
}

// A block's fold runs in the helper while the caller reads on (FoldWhileExtending): asking for the
// points, copying the state or going on after either, mid-record and at every point of the
// buffer's cycle (the kept prefix sums move to its front once per kRoomBlocks - 1 blocks), gives
// the bits of the one-thread run.
TEST(StreamingAvarTest, FoldsInFlightNeverChangeTheBits) {
  const std::vector<double> y = Record(200000, 17);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const std::vector<StreamingAvarPoint> one = Stream(y, 1024).Points();
  omp_set_num_threads(std::max(threads, 2));
  StreamingAvar stream(StreamingAvarOptions{1024});  // blocks of 2048: shared
  std::vector<StreamingAvar> copies;
  for (std::size_t i = 0; i < y.size(); i += 1000) {
    stream.Add(std::span<const double>(y).subspan(i, std::min<std::size_t>(1000, y.size() - i)));
    if (i % 7000 == 0) {
      EXPECT_FALSE(stream.Points().empty());
      copies.push_back(stream);
      copies.back().Add(std::span<const double>(y).subspan(i + 1000));
    }
  }
  omp_set_num_threads(threads);
  ASSERT_FALSE(copies.empty());
  copies.push_back(stream);
  for (const StreamingAvar& s : copies) {
    const std::vector<StreamingAvarPoint> two = s.Points();
    ASSERT_EQ(one.size(), two.size());
    for (std::size_t k = 0; k < one.size(); ++k) {
      EXPECT_EQ(std::bit_cast<std::uint64_t>(one[k].overlapping), std::bit_cast<std::uint64_t>(two[k].overlapping)) << one[k].m;
      EXPECT_EQ(std::bit_cast<std::uint64_t>(one[k].nonoverlapping), std::bit_cast<std::uint64_t>(two[k].nonoverlapping)) << one[k].m;
      EXPECT_EQ(one[k].overlapping_terms, two[k].overlapping_terms);
    }
  }
}

// The non-overlapping sums are made in different places depending on m and the exact limit (as
// the prefix sums are made, in a block's fold, or from a strided octave's ring), always term by
// term in the same order: every limit gives the same bits.
TEST(StreamingAvarTest, NonOverlappingBitsDoNotDependOnTheExactLimit) {
  const std::vector<double> y = Record(70001, 13);
  const std::vector<StreamingAvarPoint> reference = Stream(y, 64).Points();
  for (std::int64_t limit : {1, 2, 4, 8, 1024}) {
    const std::vector<StreamingAvarPoint> other = Stream(y, limit).Points();
    ASSERT_EQ(other.size(), reference.size()) << limit;
    for (std::size_t k = 0; k < other.size(); ++k) {
      EXPECT_EQ(std::bit_cast<std::uint64_t>(other[k].nonoverlapping),
                std::bit_cast<std::uint64_t>(reference[k].nonoverlapping))
          << "m = " << other[k].m << ", limit " << limit;
      EXPECT_EQ(other[k].nonoverlapping_terms, reference[k].nonoverlapping_terms);
    }
  }
}

// The exact octaves' overlapping AVAR, bit for bit, is the documented block-by-block sum: per
// block, eight partial sums of D^2 (lane k over every eighth start from the block's first, the
// last count mod 8 starts into lane 0) added in a fixed order, then one compensated addition.
// However the folds share loads between octaves or threads, these are the bits. Records of two
// or three blocks (with seven exact octaves, folded three pairs and one alone once past the
// first block): over many blocks the compensated total would absorb a block's last bit.
void ExpectBlockByBlockSums(std::int64_t samples, std::uint64_t seed) {
  const std::vector<double> y = Record(samples, seed);
  const std::int64_t limit = 64;  // kept 2 * 64 + 1 prefix sums, blocks of 2048
  const std::vector<StreamingAvarPoint> points = Stream(y, limit).Points();
  // The double-double prefix sums of y - y[0].
  std::vector<double> hi{0.0}, lo{0.0};
  for (double v : y) {
    const double x = v - y.front(), h = hi.back(), l = lo.back();
    const double t = h + x, bp = t - h;
    const double sum_lo = l + ((h - (t - bp)) + (x - bp));
    hi.push_back(t + sum_lo);
    lo.push_back(sum_lo - (hi.back() - t));
  }
  const auto n = static_cast<std::int64_t>(y.size());
  std::vector<std::pair<std::int64_t, std::int64_t>> blocks{{1, 2 * limit + 2048}};
  while (blocks.back().second < n) {
    const std::int64_t from = blocks.back().second + 1;
    blocks.push_back({from, std::min(from + 2047, n)});
  }
  std::size_t checked = 0;
  for (const StreamingAvarPoint& p : points) {
    if (p.m > limit) break;
    const std::int64_t m = p.m;
    double sum = 0, comp = 0;
    for (const auto& [from, to] : blocks) {
      if (2 * m > to) continue;
      const std::int64_t begin = std::max(from, 2 * m);
      double lanes[8] = {};
      const std::int64_t groups_end = begin + (to - begin + 1) / 8 * 8;
      for (std::int64_t a = begin; a <= to; ++a) {
        const auto i = static_cast<std::size_t>(a), b = i - m, c = i - 2 * m;
        const double d = ((hi[i] - hi[b]) - (hi[b] - hi[c])) + ((lo[i] - lo[b]) - (lo[b] - lo[c]));
        lanes[a < groups_end ? (a - begin) % 8 : 0] += d * d;
      }
      const double v = ((lanes[0] + lanes[1]) + (lanes[2] + lanes[3])) +
                       ((lanes[4] + lanes[5]) + (lanes[6] + lanes[7]));
      const double t = sum + v;
      comp += std::abs(sum) >= std::abs(v) ? (sum - t) + v : (v - t) + sum;
      sum = t;
    }
    const double expected =
        (sum + comp) / (2.0 * static_cast<double>(m) * static_cast<double>(m) *
                        static_cast<double>(n - 2 * m + 1));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(p.overlapping), std::bit_cast<std::uint64_t>(expected))
        << "m = " << m << ": " << p.overlapping << " against " << expected;
    ++checked;
  }
  EXPECT_EQ(checked, 7u);
}

TEST(StreamingAvarTest, ExactOctavesAreTheBlockByBlockSums) {
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    ExpectBlockByBlockSums(2 * 64 + 1 + 2 * 2048, seed);
    ExpectBlockByBlockSums(2 * 64 + 2 * 2048 + 1000 + static_cast<std::int64_t>(seed), seed);
  }
}

}  // namespace
}  // namespace allanlab::estimators
