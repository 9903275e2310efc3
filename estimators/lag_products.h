#pragma once
// Raw lag products of a series, sum_j a_j a_{j+k} for k = 0 .. max_lag, as the record EDF
// (estimators/record_edf.h) needs them. One fixed summation order whatever the CPU: blocks of
// kLagBlock products, each summed in eight interleaved partial sums (product j into partial
// j mod 8, the last len mod 8 products into partial 0) added as a balanced tree, the block sums
// added by a compensated sum. The vector versions compute several lags per pass over the series
// with separate multiplies and adds (no fused operations: this file is compiled with
// -ffp-contract=off), partial j mod 8 in vector lane j mod 8, so their results are bit-identical.
#include <cstdint>
#include <span>

namespace allanlab::estimators {

inline constexpr std::int64_t kLagBlock = 4096;

// Which code computes the products: kBest is the widest this CPU runs (AVX-512, AVX2, else
// portable); the others are for checking that all give the same bits.
enum class LagKernel { kBest, kAvx512, kAvx2, kPortable };

// True when this CPU runs `kernel` (always for kBest and kPortable).
bool LagKernelRuns(LagKernel kernel);

// out[k] = sum_{j=0}^{a.size()-k-1} a_j a_{j+k} for k = 0 .. out.size() - 1 (out.size() <= a.size()).
// A kernel this CPU does not run falls back on the portable code.
void LagProducts(std::span<const double> a, std::span<double> out, LagKernel kernel = LagKernel::kBest);

}  // namespace allanlab::estimators
