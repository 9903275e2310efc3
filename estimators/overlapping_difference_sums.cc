#include <algorithm>
#include <functional>
#include <numeric>
#include <utility>
#include <vector>

#include "common/piece_sharing.h"

#include "estimators/difference_kernel.h"
#include "estimators/difference_sums.h"
#include "estimators/phase_checkpoints.h"
#include "estimators/phase_integral.h"

namespace allanlab::estimators {
namespace {

// A lag-m term reads x_t, x_{t+m} (, x_{t+2m}, x_{t+3m}). One pass per lag would stream the
// record from memory once per lag (a plain loop needs ~18 ns/sample for an octave grid at
// N = 1e7), so the lags share passes arranged so that x is fetched from memory about once per
// pass, and every pass works within L2 (1 MiB per core here):
//
// * Short lags (m < kShortLimit): blocks of kBlock starts t, all short lags per block. A block
//   reads x over [t, t + kBlock + order*m), which stays in L2 for the blocks after it. Runs of
//   doubling lags share their loads (difference_kernel.h).
// * Long lags m = q R with R = kShortLimit * kTierRatio^k <= m < R * kTierRatio (every octave
//   lag, on tier k): x is viewed as rows of R samples; term t = i R + r reads column r of rows
//   i, i + q, ..., i + order*q. Walking down the rows of a strip of kStripWidth columns keeps the
//   strip's last order*kTierRatio rows in L2, so each row is fetched once for all lags of the
//   tier.
// * Other long lags (dense or explicit grids): blocks again; their far reads come from L3 or
//   memory.
// Every pass puts term t in lane t mod kLanes and flushes the lanes per block, strip or pass in a
// fixed way, so a lag's value depends only on (n, m), not on the other lags computed with it.
constexpr std::int64_t kBlock = 4096;
constexpr std::int64_t kFarBlock = 16384;
constexpr std::int64_t kShortLimit = 32768;
constexpr std::int64_t kTierRatio = 16;
constexpr std::int64_t kStripWidth = 2048;  // columns per strip: 16 KiB of each row
constexpr std::int64_t kPrefetchRows = 2;

struct LagSet {
  std::vector<std::int64_t> m;    // ascending
  std::vector<std::int64_t> end;  // number of terms n - order*m + 1, descending
  std::vector<std::size_t> slot;  // index into the caller's lags / sums
  void Add(std::int64_t lag, std::int64_t terms, std::size_t index) {
    m.push_back(lag);
    end.push_back(terms);
    slot.push_back(index);
  }
};

struct Tier {
  std::int64_t row_length = 0;
  LagSet lags;
};

struct SplitLags {
  LagSet short_lags, other_lags;
  std::vector<Tier> tiers;
};

SplitLags Split(std::int64_t n, int order, std::span<const std::int64_t> lags) {
  std::vector<std::size_t> by_lag(lags.size());
  std::iota(by_lag.begin(), by_lag.end(), std::size_t{0});
  std::stable_sort(by_lag.begin(), by_lag.end(),
                   [&](std::size_t a, std::size_t b) { return lags[a] < lags[b]; });
  SplitLags split;
  for (std::size_t slot : by_lag) {
    const std::int64_t m = lags[slot];
    const std::int64_t terms = n - order * m + 1;
    if (m < kShortLimit) {
      split.short_lags.Add(m, terms, slot);
      continue;
    }
    std::int64_t row_length = kShortLimit;
    std::size_t tier = 0;
    while (m / row_length >= kTierRatio) {
      row_length *= kTierRatio;
      ++tier;
    }
    if (m % row_length != 0) {
      split.other_lags.Add(m, terms, slot);
      continue;
    }
    if (split.tiers.size() <= tier) split.tiers.resize(tier + 1);
    split.tiers[tier].row_length = row_length;
    split.tiers[tier].lags.Add(m, terms, slot);
  }
  return split;
}

class Accumulators {
 public:
  explicit Accumulators(std::size_t count) : lanes_(count, Lanes{}), totals_(count) {}
  Lanes* lanes(std::size_t slot) { return &lanes_[slot]; }
  void Flush(std::size_t slot) {
    totals_[slot].Add(SumLanes(lanes_[slot]));
    lanes_[slot] = Lanes{};
  }
  double Total(std::size_t slot) const { return totals_[slot].Value(); }

 private:
  std::vector<Lanes> lanes_;
  std::vector<CompensatedSum> totals_;
};

// Terms [lo, hi) of every lag of the set that still has terms there; a run of doubling lags
// (m, 2m, 4m, ...) goes through one chain call that shares their loads.
// `visit(j)` follows each lag's accumulation.
template <typename Acc, typename Visit>
void ForEachActiveLag(const LagSet& set, int order, std::int64_t lo, std::int64_t hi,
                      const double* x, Acc* acc, Visit&& visit) {
  const std::size_t count = set.m.size();
  for (std::size_t j = 0; j < count && lo < set.end[j];) {
    std::size_t chain = 1;
    if (order == 2) {
      while (chain < static_cast<std::size_t>(kMaxChain) && j + chain < count &&
             set.m[j + chain] == 2 * set.m[j + chain - 1] && lo < set.end[j + chain]) {
        ++chain;
      }
    }
    if (chain == 1) {
      AccumulateSquaredDifferences(x, order, set.m[j], lo, std::min(hi, set.end[j]),
                                   acc->lanes(set.slot[j]));
      visit(j++);
      continue;
    }
    // Together while the widest lag of the chain has terms, then each on its own.
    const std::int64_t common = std::min(hi, set.end[j + chain - 1]);
    Lanes* lanes[kMaxChain];
    for (std::size_t k = 0; k < chain; ++k) lanes[k] = acc->lanes(set.slot[j + k]);
    AccumulateSquaredSecondDifferencesChain(x, set.m[j], static_cast<int>(chain), lo, common,
                                            lanes);
    for (std::size_t k = 0; k < chain; ++k, ++j) {
      AccumulateSquaredDifferences(x, order, set.m[j], common, std::min(hi, set.end[j]), lanes[k]);
      visit(j);
    }
  }
}

// `before_block(last)` runs before each block with the last phase index the block reads.
template <typename BeforeBlock>
void BlockPass(const double* x, int order, std::int64_t block, const LagSet& set, Accumulators* acc,
               BeforeBlock&& before_block) {
  if (set.m.empty()) return;
  const std::int64_t reach = order * set.m.back();
  for (std::int64_t start = 0; start < set.end[0]; start += block) {
    before_block(start + block - 1 + reach);
    ForEachActiveLag(set, order, start, start + block, x, acc,
                     [&](std::size_t j) { acc->Flush(set.slot[j]); });
  }
}

void RowPass(const double* x, std::int64_t n, int order, const Tier& tier, Accumulators* acc) {
  const LagSet& set = tier.lags;
  if (set.m.empty()) return;
  const std::int64_t r = tier.row_length;
  for (std::int64_t column = 0; column < r; column += kStripWidth) {
    std::size_t widest = set.m.size() - 1;  // largest lag still active
    for (std::int64_t base = column; base < set.end[0]; base += r) {
      while (base >= set.end[widest]) --widest;
      // The row the widest lag reaches a few rows on is not in cache yet, and the hardware
      // prefetcher cannot guess a jump of a whole row: ask for it.
      const std::int64_t ahead = base + kPrefetchRows * r + order * set.m[widest];
      if (ahead + kStripWidth <= n + 1) {
        for (std::int64_t k = 0; k < kStripWidth; k += 8) __builtin_prefetch(x + ahead + k, 0, 3);
      }
      ForEachActiveLag(set, order, base, base + kStripWidth, x, acc, [](std::size_t) {});
    }
    for (std::size_t j = 0; j < set.m.size(); ++j) acc->Flush(set.slot[j]);
  }
}

void LongPasses(const double* x, std::int64_t n, int order, const SplitLags& split,
                Accumulators* acc) {
  for (const Tier& tier : split.tiers) RowPass(x, n, order, tier, acc);
  BlockPass(x, order, kFarBlock, split.other_lags, acc, [](std::int64_t) {});
}

// Integrates the phase up to (at least) x_upto, in pieces that start at multiples of 8 so that
// the bits do not depend on where the pieces end (phase_integral.h).
class LazyPhase {
 public:
  LazyPhase(std::span<const double> rate, double reference, std::span<double> phase)
      : rate_(rate), reference_(reference), phase_(phase) {
    phase_[0] = 0.0;
  }
  void EnsureUpTo(std::int64_t upto) {
    const auto n = static_cast<std::int64_t>(rate_.size());
    if (upto <= done_) return;
    upto = std::min(n, (upto + kPiece - 1) / kPiece * kPiece);
    const auto from = static_cast<std::size_t>(done_);
    const auto count = static_cast<std::size_t>(upto - done_);
    ContinueIntegral(rate_.subspan(from, count), reference_, phase_.subspan(from, count + 1));
    done_ = upto;
  }

 private:
  static constexpr std::int64_t kPiece = 8;
  std::span<const double> rate_;
  double reference_;
  std::span<double> phase_;
  std::int64_t done_ = 0;  // phase_[0..done_] is final
};


// ---- Without an N-sized phase (SumOverlappingDifferencesFromCheckpoints). Fresh pages for N + 1
// phase doubles cost more in this VM than the whole octave curve (measured ~4.5 ns per sample
// for first touch), so the phase is rebuilt from the checkpoints of one integration pass
// (phase_checkpoints.h) in buffers that stay in cache:
// * short lags: a sliding window of x, integrated just ahead of the blocks that read it, from the
//   checkpoint at the first block of a piece of kPieceBlocks blocks;
// * tiers: a strip of kStripWidth columns of each row, rebuilt from the checkpoint x_{kR + c}, in
//   a window of consecutive rows stored kStripWidth apart, so that lag q R of the record is lag
//   q kStripWidth of the window; one strip is one piece.
// The same kernel calls see the same x bits over the same term ranges, with term indices shifted
// by multiples of kLanes, so every flush has the bits of IntegrateAndSumOverlappingDifferences.
// Pieces depend on nothing but the checkpoints, so a helper thread takes some of them; each piece
// keeps its flushes, and they reach the compensated totals in piece order, the order of the pass
// above: the bits do not depend on which thread ran a piece.
constexpr std::int64_t kPieceBlocks = 64;
static_assert(kShortLimit % PhaseCheckpoints::kStride == 0 && kBlock % kLanes == 0 &&
              kStripWidth % PhaseCheckpoints::kStride == 0 && kBlock % PhaseCheckpoints::kStride == 0);
// Below this many samples a pass takes well under a millisecond: no helper.
constexpr std::int64_t kSharedPassSamples = std::int64_t{1} << 20;

// lags with their term ends moved to a window whose index 0 is the record's index `base`, and
// lags scaled (tiers); ends clamped to [lo, lo + width] for the window range [lo, lo + width).
void ShiftLags(const LagSet& from, std::int64_t base, std::int64_t lo, std::int64_t width,
               std::int64_t scale_num, std::int64_t scale_den, LagSet* to) {
  for (std::size_t j = 0; j < from.m.size(); ++j) {
    to->m[j] = from.m[j] / scale_den * scale_num;
    to->end[j] = lo + std::clamp<std::int64_t>(from.end[j] - base, 0, width);
  }
}

// The flushes one piece made, in order, for the totals.
using Flushes = std::vector<std::pair<std::size_t, double>>;

// A piece's lane sums while it runs (a few KiB, not kept), and its flushes.
class PieceAccumulators {
 public:
  PieceAccumulators(std::size_t count, Flushes* flushed) : lanes_(count, Lanes{}), flushed_(*flushed) {}
  Lanes* lanes(std::size_t slot) { return &lanes_[slot]; }
  void Flush(std::size_t slot) {
    flushed_.emplace_back(slot, SumLanes(lanes_[slot]));
    lanes_[slot] = Lanes{};
  }

 private:
  std::vector<Lanes> lanes_;
  Flushes& flushed_;
};

// x[base .. done] of the record in a window that slides forward, integrated from a checkpoint.
class WindowedPhase {
 public:
  // Starts at x_from (from a multiple of the checkpoint stride) with room for `span` samples.
  WindowedPhase(const PhaseCheckpoints& x, std::int64_t span, std::int64_t from, std::vector<double>* window)
      : x_(x), window_(*window), base_(from), done_(from) {
    window_.resize(static_cast<std::size_t>(4 * span + 8));
    window_[0] = x.At(from);
  }
  // Makes x[from .. upto] available (from a multiple of kLanes, never decreasing); returns the
  // window pointer whose index 0 is x_base().
  const double* Ensure(std::int64_t from, std::int64_t upto) {
    const std::int64_t n = x_.size();
    upto = std::min(upto, n);
    if (upto - base_ >= static_cast<std::int64_t>(window_.size()) - 8) {
      std::copy(window_.begin() + (from - base_), window_.begin() + (done_ - base_ + 1), window_.begin());
      base_ = from;
    }
    if (upto > done_) {
      upto = std::min(n, (upto + 7) / 8 * 8);
      const auto count = static_cast<std::size_t>(upto - done_);
      ContinueIntegral(x_.rate().subspan(static_cast<std::size_t>(done_), count), x_.reference(),
                       std::span<double>(window_).subspan(static_cast<std::size_t>(done_ - base_), count + 1));
      done_ = upto;
    }
    return window_.data();
  }
  std::int64_t base() const { return base_; }

 private:
  const PhaseCheckpoints& x_;
  std::vector<double>& window_;  // x[base_ .. done_] at [0 .. done_ - base_]
  std::int64_t base_, done_;
};

// Blocks [first_block, end_block) of the short-lag pass.
void WindowedBlockPiece(const PhaseCheckpoints& x, int order, const LagSet& set, std::int64_t first_block,
                        std::int64_t end_block, PieceAccumulators* acc) {
  static thread_local std::vector<double> window;
  const std::int64_t reach = order * set.m.back();
  WindowedPhase phase(x, kBlock + reach, first_block * kBlock, &window);
  LagSet shifted = set;
  for (std::int64_t start = first_block * kBlock; start < set.end[0] && start < end_block * kBlock;
       start += kBlock) {
    const double* w = phase.Ensure(start, start + kBlock - 1 + reach);
    const std::int64_t base = phase.base();
    for (std::size_t j = 0; j < set.m.size(); ++j) shifted.end[j] = set.end[j] - base;
    ForEachActiveLag(shifted, order, start - base, start - base + kBlock, w, acc,
                     [&](std::size_t j) { acc->Flush(set.slot[j]); });
  }
}

// One strip (columns [column, column + kStripWidth)) of RowPass, its rows rebuilt from the
// checkpoints.
void RebuiltStripPiece(const PhaseCheckpoints& x, int order, const Tier& tier, std::int64_t column,
                       PieceAccumulators* acc) {
  static thread_local std::vector<double> rows;
  const LagSet& set = tier.lags;
  const std::int64_t n = x.size();
  const std::int64_t r = tier.row_length;
  const std::int64_t w = kStripWidth;
  const std::int64_t reach_rows = order * (set.m.back() / r);
  const std::int64_t capacity = 2 * (reach_rows + 1);  // rows in the window
  rows.resize(static_cast<std::size_t>(capacity * w + 1));
  LagSet shifted = set;
  std::int64_t first_row = 0, built = 0;  // window rows: [first_row, built)
  for (std::int64_t row = 0; column + row * r < set.end[0]; ++row) {
    const std::int64_t need = row + reach_rows + 1;
    if (need - first_row > capacity) {
      std::copy(rows.begin() + (row - first_row) * w, rows.begin() + (built - first_row) * w, rows.begin());
      first_row = row;
    }
    for (; built < need; ++built) {
      const std::int64_t start = column + built * r;
      if (start > n) break;
      const std::int64_t count = std::min(w, n - start);
      double* out = rows.data() + (built - first_row) * w;
      out[0] = x.At(start);
      ContinueIntegral(x.rate().subspan(static_cast<std::size_t>(start), static_cast<std::size_t>(count)),
                       x.reference(), {out, static_cast<std::size_t>(count + 1)});
    }
    const std::int64_t lo = (row - first_row) * w;
    ShiftLags(set, column + row * r, lo, w, w, r, &shifted);
    ForEachActiveLag(shifted, order, lo, lo + w, rows.data(), acc, [](std::size_t) {});
  }
  for (std::size_t j = 0; j < set.m.size(); ++j) acc->Flush(set.slot[j]);
}

}  // namespace

void OverlappingDifferenceSums(std::span<const double> phase, int order,
                               std::span<const std::int64_t> lags, std::span<double> sums) {
  const auto n = static_cast<std::int64_t>(phase.size()) - 1;
  const SplitLags split = Split(n, order, lags);
  Accumulators acc(lags.size());
  BlockPass(phase.data(), order, kBlock, split.short_lags, &acc, [](std::int64_t) {});
  LongPasses(phase.data(), n, order, split, &acc);
  for (std::size_t slot = 0; slot < lags.size(); ++slot) sums[slot] = acc.Total(slot);
}

void IntegrateAndSumOverlappingDifferences(std::span<const double> rate, double reference,
                                           int order, std::span<const std::int64_t> lags,
                                           std::span<double> phase, std::span<double> sums,
                                           const PhaseReady* phase_ready) {
  const auto n = static_cast<std::int64_t>(rate.size());
  const SplitLags split = Split(n, order, lags);
  Accumulators acc(lags.size());
  LazyPhase lazy(rate, reference, phase);
  BlockPass(phase.data(), order, kBlock, split.short_lags, &acc,
            [&](std::int64_t last) { lazy.EnsureUpTo(last); });
  lazy.EnsureUpTo(n);
  const std::function<void()> rest = [&] { LongPasses(phase.data(), n, order, split, &acc); };
  if (phase_ready != nullptr) {
    (*phase_ready)(rest);
  } else {
    rest();
  }
  for (std::size_t slot = 0; slot < lags.size(); ++slot) sums[slot] = acc.Total(slot);
}

bool SumOverlappingDifferencesFromCheckpoints(const PhaseCheckpoints& x, int order,
                                              std::span<const std::int64_t> lags, std::span<double> sums) {
  const std::int64_t n = x.size();
  const SplitLags split = Split(n, order, lags);
  if (!split.other_lags.m.empty()) return false;
  // The pieces: every strip of every tier, then the short-lag blocks kPieceBlocks at a time.
  struct Piece {
    const Tier* tier = nullptr;
    std::int64_t first = 0;  // the strip's column, or the first block
  };
  std::vector<Piece> pieces;
  for (const Tier& tier : split.tiers) {
    if (tier.lags.m.empty()) continue;
    for (std::int64_t column = 0; column < tier.row_length; column += kStripWidth) pieces.push_back({&tier, column});
  }
  if (!split.short_lags.m.empty()) {
    const std::int64_t blocks = (split.short_lags.end[0] + kBlock - 1) / kBlock;
    for (std::int64_t b = 0; b < blocks; b += kPieceBlocks) pieces.push_back({nullptr, b});
  }
  std::vector<Flushes> flushes(pieces.size());
  const std::function<void(int)> run = [&](int p) {
    const Piece& piece = pieces[static_cast<std::size_t>(p)];
    PieceAccumulators a(lags.size(), &flushes[static_cast<std::size_t>(p)]);
    if (piece.tier != nullptr) {
      RebuiltStripPiece(x, order, *piece.tier, piece.first, &a);
    } else {
      WindowedBlockPiece(x, order, split.short_lags, piece.first, piece.first + kPieceBlocks, &a);
    }
  };
  const int count = static_cast<int>(pieces.size());
  if (n >= kSharedPassSamples && PieceSharing::Useful()) {
    PieceSharing sharing;
    sharing.Run(count, run);
  } else {
    for (int p = 0; p < count; ++p) run(p);
  }
  std::vector<CompensatedSum> totals(lags.size());
  for (const Flushes& piece : flushes) {
    for (const auto& [slot, value] : piece) totals[slot].Add(value);
  }
  for (std::size_t slot = 0; slot < lags.size(); ++slot) sums[slot] = totals[slot].Value();
  return true;
}

bool FitsCheckpointPass(std::int64_t n, int order, std::span<const std::int64_t> lags) {
  return Split(n, order, lags).other_lags.m.empty();
}

bool SumOverlappingDifferencesFromRate(std::span<const double> rate, double reference, int order,
                                       std::span<const std::int64_t> lags, std::span<double> sums,
                                       double* last_phase) {
  if (!FitsCheckpointPass(static_cast<std::int64_t>(rate.size()), order, lags)) return false;
  const PhaseCheckpoints x(rate, reference);
  *last_phase = x.Last();
  return SumOverlappingDifferencesFromCheckpoints(x, order, lags, sums);
}

}  // namespace allanlab::estimators
