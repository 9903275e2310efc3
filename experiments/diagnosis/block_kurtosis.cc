#include "experiments/diagnosis/block_kurtosis.h"

#include <limits>

namespace allanlab::experiments {
namespace {

constexpr int kLanes = 4;  // independent partial sums: chains of additions overlap

// Sums of consecutive blocks of m samples of `rate` (the trailing partial block dropped).
std::vector<double> BlockSums(std::span<const double> rate, std::int64_t m) {
  const std::int64_t blocks = static_cast<std::int64_t>(rate.size()) / m;
  std::vector<double> sums(static_cast<std::size_t>(blocks));
  if (m == 1) {
    // The loop below for one-sample blocks, without its per-block set-up (the first octave is a
    // record-sized pass): its sum (lane[0] + 0) + (0 + 0) with lane[0] = 0 + x is x + 0, the
    // sample itself with -0 made +0.
    for (std::int64_t b = 0; b < blocks; ++b) sums[static_cast<std::size_t>(b)] = rate[static_cast<std::size_t>(b)] + 0.0;
    return sums;
  }
  for (std::int64_t b = 0; b < blocks; ++b) {
    double lane[kLanes] = {};
    std::int64_t k = 0;
    const double* x = rate.data() + b * m;
    for (; k + kLanes <= m; k += kLanes) {
      for (int l = 0; l < kLanes; ++l) lane[l] += x[k + l];
    }
    for (; k < m; ++k) lane[0] += x[k];
    sums[static_cast<std::size_t>(b)] = (lane[0] + lane[1]) + (lane[2] + lane[3]);
  }
  return sums;
}

// Blocks of 2m from blocks of m: adjacent pairs (a trailing odd block dropped, as BlockSums does).
void PairUp(std::vector<double>* sums) {
  const std::size_t half = sums->size() / 2;
  for (std::size_t b = 0; b < half; ++b) (*sums)[b] = (*sums)[2 * b] + (*sums)[2 * b + 1];
  sums->resize(half);
}

double ExcessKurtosisOfIncrements(const std::vector<double>& sums) {
  if (sums.size() < 3) return std::numeric_limits<double>::quiet_NaN();
  const std::size_t n = sums.size() - 1;
  double lane[kLanes] = {};
  std::size_t i = 0;
  for (; i + kLanes <= n; i += kLanes) {
    for (int l = 0; l < kLanes; ++l) lane[l] += sums[i + l + 1] - sums[i + l];
  }
  for (; i < n; ++i) lane[0] += sums[i + 1] - sums[i];
  const double mean = ((lane[0] + lane[1]) + (lane[2] + lane[3])) / static_cast<double>(n);
  double m2[kLanes] = {}, m4[kLanes] = {};
  for (i = 0; i + kLanes <= n; i += kLanes) {
    for (int l = 0; l < kLanes; ++l) {
      const double d = sums[i + l + 1] - sums[i + l] - mean;
      m2[l] += d * d;
      m4[l] += d * d * d * d;
    }
  }
  for (; i < n; ++i) {
    const double d = sums[i + 1] - sums[i] - mean;
    m2[0] += d * d;
    m4[0] += d * d * d * d;
  }
  const double s2 = (m2[0] + m2[1]) + (m2[2] + m2[3]);
  const double s4 = (m4[0] + m4[1]) + (m4[2] + m4[3]);
  if (!(s2 > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  return static_cast<double>(n) * s4 / (s2 * s2) - 3.0;
}

}  // namespace

std::vector<double> BlockIncrementKurtosis(std::span<const double> rate, std::span<const std::int64_t> ms) {
  std::vector<double> out;
  std::vector<double> sums;
  std::int64_t level = 0;  // the m `sums` holds
  for (std::int64_t m : ms) {
    if (level > 0 && m == 2 * level) {
      PairUp(&sums);
    } else {
      sums = BlockSums(rate, m);
    }
    level = m;
    out.push_back(ExcessKurtosisOfIncrements(sums));
  }
  return out;
}

}  // namespace allanlab::experiments
