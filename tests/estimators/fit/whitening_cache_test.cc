// The cached whitening answers as the function it wraps, bit for bit, forms each distinct x once
// while it is kept, and shares what it keeps between copies.
#include <gtest/gtest.h>

#include <cstring>

#include "estimators/fit/whitening_cache.h"

namespace allanlab::estimators {
namespace {

// A stand-in for a covariance model's whitening: W depends on x alone; x(0) < 0 fails.
bool Toy(const Eigen::VectorXd& x, Eigen::MatrixXd* w) {
  if (x(0) < 0.0) return false;
  *w = Eigen::MatrixXd::Identity(3, 3) * (1.0 + x.squaredNorm());
  (*w)(2, 0) = std::sin(x(1));
  return true;
}

bool SameBits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
}

TEST(WhiteningCache, SameBitsAsTheWrappedFunctionAndEachXFormedOnce) {
  int calls = 0;
  const WhiteningFunction cached = CachedWhitening([&calls](const Eigen::VectorXd& x, Eigen::MatrixXd* w) {
    ++calls;
    return Toy(x, w);
  });
  const Eigen::Vector2d a(0.3, 1.7), b(0.1 + 0.2, 1.7), failing(-1.0, 0.0);
  Eigen::MatrixXd direct, first, again;
  ASSERT_TRUE(Toy(a, &direct));
  ASSERT_TRUE(cached(a, &first));
  ASSERT_TRUE(cached(a, &again));
  EXPECT_TRUE(SameBits(direct, first));
  EXPECT_TRUE(SameBits(direct, again));
  EXPECT_EQ(calls, 1);
  // 0.1 + 0.2 differs from 0.3 in its last bit: another key.
  ASSERT_TRUE(cached(b, &again));
  EXPECT_EQ(calls, 2);
  EXPECT_FALSE(cached(failing, &again));
  EXPECT_FALSE(cached(failing, &again));
  EXPECT_EQ(calls, 3);
  // A copy (LinearProblem is copied by value along the profile) shares the answers kept.
  const WhiteningFunction copy = cached;
  ASSERT_TRUE(copy(a, &again));
  EXPECT_EQ(calls, 3);
}

TEST(WhiteningCache, FormsAgainOnceEvicted) {
  int calls = 0;
  const WhiteningFunction cached = CachedWhitening(
      [&calls](const Eigen::VectorXd& x, Eigen::MatrixXd* w) {
        ++calls;
        return Toy(x, w);
      },
      2);
  Eigen::MatrixXd w;
  for (double v : {1.0, 2.0, 3.0}) cached(Eigen::Vector2d(v, 0.0), &w);  // 1.0 evicted by 3.0
  EXPECT_EQ(calls, 3);
  cached(Eigen::Vector2d(3.0, 0.0), &w);
  EXPECT_EQ(calls, 3);
  cached(Eigen::Vector2d(1.0, 0.0), &w);
  EXPECT_EQ(calls, 4);
  Eigen::MatrixXd direct;
  Toy(Eigen::Vector2d(1.0, 0.0), &direct);
  EXPECT_TRUE(SameBits(direct, w));
}

}  // namespace
}  // namespace allanlab::estimators
