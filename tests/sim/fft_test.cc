// The real FFT built on a half-length complex transform equals the naive DFT and inverts.
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "sim/fft.h"
#include "sim/seeding.h"

namespace allanlab::sim {
namespace {

TEST(RealFft, MatchesNaiveDftAndInverts) {
  for (std::size_t n : {2, 4, 6, 30, 64, 210, 2048 + 2}) {
    Engine engine(n);
    std::vector<double> x(n);
    for (double& v : x) v = static_cast<double>(engine() >> 11) * 0x1p-53 - 0.5;
    std::vector<double> buffer(n + 2, 0.0);
    std::copy(x.begin(), x.end(), buffer.begin());
    ForwardRealFft(n, buffer.data());
    for (std::size_t k = 0; k <= n / 2; ++k) {
      std::complex<double> expected = 0.0;
      for (std::size_t j = 0; j < n; ++j) {
        expected += x[j] * std::polar(1.0, -2.0 * std::numbers::pi * static_cast<double>(j * k % n) / n);
      }
      EXPECT_NEAR(buffer[2 * k], expected.real(), 1e-10) << "n=" << n << " k=" << k;
      EXPECT_NEAR(buffer[2 * k + 1], expected.imag(), 1e-10) << "n=" << n << " k=" << k;
    }
    InverseRealFft(n, buffer.data());
    for (std::size_t j = 0; j < n; ++j) EXPECT_NEAR(buffer[j] / n, x[j], 1e-13) << "n=" << n;
  }
}

TEST(GoodFftSize, SevenSmoothAndMinimal) {
  EXPECT_EQ(GoodFftSize(1), 1u);
  EXPECT_EQ(GoodFftSize(11), 12u);
  EXPECT_EQ(GoodFftSize(4194305), 4199040u);  // 2^7 3^8 5... is the next 7-smooth
}

}  // namespace
// The kept twiddles are the rotation the transforms ran before they were kept: from k = 1 by
// products with e^{-2 pi i / n}, re-anchored with sin/cos every 512 steps, the same bits.
TEST(RealFftTwiddles, KeptTableIsTheRotationsBits) {
  for (std::size_t n : {std::size_t{1000}, std::size_t{16384}, std::size_t{2000000}}) {
    const auto table = RealFftTwiddles(n);
    ASSERT_TRUE(table != nullptr);
    ASSERT_EQ(table->size(), n / 4 + 1);
    const std::complex<double> step = std::polar(1.0, -2.0 * std::numbers::pi / static_cast<double>(n));
    std::complex<double> current = 1.0;
    for (std::size_t k = 1; k <= n / 4; ++k) {
      current = k == 1 || k % 512 == 0 ? std::polar(1.0, -2.0 * std::numbers::pi * static_cast<double>(k) / static_cast<double>(n))
                                       : MulFinite(current, step);
      ASSERT_EQ((*table)[k], current) << "n " << n << " k " << k;
    }
    EXPECT_EQ(RealFftTwiddles(n), table);  // kept, not remade
  }
  EXPECT_EQ(RealFftTwiddles((std::size_t{1} << 22) + 8), nullptr);  // too long to keep
}

}  // namespace allanlab::sim
