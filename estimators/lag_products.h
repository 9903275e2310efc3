#pragma once
// Raw lag products of a series, sum_j a_j a_{j+k} for k = 0 .. max_lag, as the record EDF
// (estimators/record_edf.h) needs them. One fixed summation order whatever the CPU: blocks of
// kLagBlock products, each summed in eight interleaved partial sums (product j into partial
// j mod 8, the last len mod 8 products into partial 0) added as a balanced tree, the block sums
// added by a compensated sum. The AVX2 version computes four lags per pass over the series with
// separate multiplies and adds (no fused operations), so its results are bit-identical.
#include <cstdint>
#include <span>

namespace allanlab::estimators {

inline constexpr std::int64_t kLagBlock = 4096;

// out[k] = sum_{j=0}^{a.size()-k-1} a_j a_{j+k} for k = 0 .. out.size() - 1 (out.size() <= a.size()).
// `vector_units`: false runs the portable code on any CPU (to check that both agree).
void LagProducts(std::span<const double> a, std::span<double> out, bool vector_units = true);

}  // namespace allanlab::estimators
