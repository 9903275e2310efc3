#include "estimators/streaming_avar.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "common/piece_sharing.h"

namespace allanlab::estimators {
namespace {

// Neumaier's compensated sum: the lost low part of each addition is kept in *comp.
void CompensatedAdd(double* sum, double* comp, double v) {
  const double t = *sum + v;
  *comp += std::abs(*sum) >= std::abs(v) ? (*sum - t) + v : (v - t) + *sum;
  *sum = t;
}

// D = S_a - 2 S_b + S_c from double-double prefix sums. Neighbouring prefix sums are close, so the
// differences of the high parts are exact (Sterbenz) and the low parts carry what the high parts
// rounded away.
inline double SecondDifference(double a_hi, double a_lo, double b_hi, double b_lo, double c_hi,
                               double c_lo) {
  return ((a_hi - b_hi) - (b_hi - c_hi)) + ((a_lo - b_lo) - (b_lo - c_lo));
}

// Sum of D^2 over the block indices a = first .. last, D at lag m from S_a, S_{a-m}, S_{a-2m}.
// Eight partial sums, each over every eighth index, added in a fixed order: every version below
// gives the same bits, whatever vector width the compiler uses for the eight lanes.
__attribute__((always_inline)) inline double SquaresBody(const double* hi, const double* lo,
                                                         std::int64_t first, std::int64_t last,
                                                         std::int64_t m) {
  double lanes[8] = {};
  std::int64_t i = first;
  for (; i + 8 <= last + 1; i += 8) {
    for (int k = 0; k < 8; ++k) {
      const std::int64_t a = i + k;
      const double d =
          SecondDifference(hi[a], lo[a], hi[a - m], lo[a - m], hi[a - 2 * m], lo[a - 2 * m]);
      lanes[k] += d * d;
    }
  }
  for (; i <= last; ++i) {
    const double d =
        SecondDifference(hi[i], lo[i], hi[i - m], lo[i - m], hi[i - 2 * m], lo[i - 2 * m]);
    lanes[0] += d * d;
  }
  return ((lanes[0] + lanes[1]) + (lanes[2] + lanes[3])) +
         ((lanes[4] + lanes[5]) + (lanes[6] + lanes[7]));
}

double PortableSquares(const double* hi, const double* lo, std::int64_t first, std::int64_t last,
                       std::int64_t m) {
  return SquaresBody(hi, lo, first, last, m);
}

#if defined(__x86_64__) && defined(__GNUC__)
// No FMA: a fused d * d + lane would round differently from the portable version.
__attribute__((target("avx2"))) double Avx2Squares(const double* hi, const double* lo,
                                                   std::int64_t first, std::int64_t last,
                                                   std::int64_t m) {
  return SquaresBody(hi, lo, first, last, m);
}
#endif

using SquaresFn = double (*)(const double*, const double*, std::int64_t, std::int64_t, std::int64_t);

SquaresFn BlockSquares() {
#if defined(__x86_64__) && defined(__GNUC__)
  static const SquaresFn best = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") ? Avx2Squares : PortableSquares;
  }();
  return best;
#else
  return PortableSquares;
#endif
}

}  // namespace

bool StreamingAvarOptions::IsValid(std::string* why) const {
  if (exact_overlap_max_m < 1 ||
      !std::has_single_bit(static_cast<std::uint64_t>(exact_overlap_max_m))) {
    if (why) {
      *why = "exact_overlap_max_m must be a power of two >= 1, got " +
             std::to_string(exact_overlap_max_m);
    }
    return false;
  }
  return true;
}

StreamingAvar::StreamingAvar(StreamingAvarOptions options) : options_(options) {
  if (!options_.IsValid(nullptr)) options_ = StreamingAvarOptions();
  const std::int64_t largest = options_.exact_overlap_max_m;
  for (std::int64_t m = 1; m <= largest; m *= 2) {
    exact_.push_back({m, {}});
    if (m > std::numeric_limits<std::int64_t>::max() / 2) break;
  }
  // Kept: 2 largest + 1 prefix sums; the block: as many again (at least 2048), so that moving
  // the kept ones to the front costs at most one copy per new value.
  const std::uint64_t limit = std::numeric_limits<std::size_t>::max() / 32;
  const std::uint64_t kept = std::min<std::uint64_t>(static_cast<std::uint64_t>(largest) * 2 + 1, limit);
  const std::uint64_t block = std::max<std::uint64_t>(kept - 1, 2048);
  kept_ = static_cast<std::size_t>(kept);
  capacity_ = static_cast<std::size_t>(kept + block);
  const std::size_t reserved = std::min<std::size_t>(capacity_, std::size_t{1} << 17);
  hi_.reserve(reserved);
  lo_.reserve(reserved);
  hi_.push_back(0.0);  // S_0
  lo_.push_back(0.0);
  short_nonoverlap_ = std::min<std::int64_t>(largest, 2);
  if (PieceSharing::Useful()) sharing_ = std::make_shared<PieceSharing>();
}

const StreamingAvar::DoubleDouble& StreamingAvar::Octave::Back(std::int64_t k) const {
  std::int64_t index = head - 1 - k;
  if (index < 0) index += static_cast<std::int64_t>(ring.size());
  return ring[static_cast<std::size_t>(index)];
}

void StreamingAvar::Push(Octave* o, const DoubleDouble& s, std::int64_t n) {
  o->ring[static_cast<std::size_t>(o->head)] = s;
  if (++o->head == static_cast<std::int64_t>(o->ring.size())) o->head = 0;
  ++o->pushed;
  o->last_index = n;
  if (o->pushed < 2 * o->span + 1) return;
  const DoubleDouble& a = o->Back(0);
  const DoubleDouble& b = o->Back(o->span);
  const DoubleDouble& c = o->Back(2 * o->span);
  const double d = SecondDifference(a.hi, a.lo, b.hi, b.lo, c.hi, c.lo);
  CompensatedAdd(&o->sums.o_sum, &o->sums.o_comp, d * d);
  ++o->sums.o_terms;
  if ((n & (o->m - 1)) == 0) {  // m is a power of two: no division per push
    CompensatedAdd(&o->sums.n_sum, &o->sums.n_comp, d * d);
    ++o->sums.n_terms;
  }
}

void StreamingAvar::PushRun(Octave* o, std::int64_t t_first, std::int64_t t_last) {
  const std::int64_t stride = o->stride;
  std::int64_t t = t_first;
  // Until the ring is full a push makes no term: these go one at a time (once per octave).
  for (; t <= t_last && o->pushed + 1 < 2 * o->span + 1; t += stride) Push(o, PrefixAt(t), t);
  if (t > t_last) return;
  // The ring holds 2 span + 1 values, so with the new one written at h, Back(span) is at h - span
  // and Back(2 span) at h + 1 (mod its size): three positions that each advance by one per push,
  // and the same terms, in the same order, as Push.
  const std::int64_t size = static_cast<std::int64_t>(o->ring.size());
  DoubleDouble* const ring = o->ring.data();
  std::int64_t h = o->head;
  std::int64_t b = h - o->span < 0 ? h - o->span + size : h - o->span;
  std::int64_t c = h + 1 == size ? 0 : h + 1;
  const std::int64_t m_mask = o->m - 1;  // m is a power of two
  Sums sums = o->sums;
  const double* const hi = hi_.data();
  const double* const lo = lo_.data();
  std::int64_t pushes = 0;
  for (; t <= t_last; t += stride, ++pushes) {
    const auto i = static_cast<std::size_t>(t - first_);
    const double a_hi = hi[i], a_lo = lo[i];
    ring[h] = {a_hi, a_lo};
    const double d = SecondDifference(a_hi, a_lo, ring[b].hi, ring[b].lo, ring[c].hi, ring[c].lo);
    CompensatedAdd(&sums.o_sum, &sums.o_comp, d * d);
    if ((t & m_mask) == 0) {
      CompensatedAdd(&sums.n_sum, &sums.n_comp, d * d);
      ++sums.n_terms;
    }
    if (++h == size) h = 0;
    if (++b == size) b = 0;
    if (++c == size) c = 0;
  }
  sums.o_terms += pushes;
  o->sums = sums;
  o->head = h;
  o->pushed += pushes;
  o->last_index = t - stride;
}

StreamingAvar::DoubleDouble StreamingAvar::PrefixAt(std::int64_t n) const {
  const auto i = static_cast<std::size_t>(n - first_);
  return {hi_[i], lo_[i]};
}

void StreamingAvar::StartNextOctave() {
  Octave next;
  if (octaves_.empty()) {
    // The first strided octave: the block still holds S_0 .. S_{next.m}.
    next.m = 2 * exact_.back().m;
    next.stride = 2;
    next.span = next.m / next.stride;
    next.ring.resize(static_cast<std::size_t>(2 * next.span + 1));
    for (std::int64_t k = 0; k <= next.m; k += next.stride) Push(&next, PrefixAt(k), k);
    octaves_.push_back(std::move(next));
    return;
  }
  const Octave& last = octaves_.back();
  next.m = 2 * last.m;
  next.stride = std::max<std::int64_t>(1, next.m / options_.exact_overlap_max_m);
  next.span = next.m / next.stride;
  next.ring.resize(static_cast<std::size_t>(2 * next.span + 1));
  // `last` has just pushed S_0 .. S_{2 last.m} = S_{next.m} at its stride: everything the new
  // octave would have seen had it run from the start.
  const std::int64_t step = next.stride / last.stride;
  for (std::int64_t k = 0; k <= 2 * last.span; k += step) {
    Push(&next, last.Back(2 * last.span - k), k * last.stride);
  }
  octaves_.push_back(std::move(next));
}

void StreamingAvar::FoldExact(ExactOctave* o, std::int64_t from, std::int64_t to) const {
  const double* hi = hi_.data();
  const double* lo = lo_.data();
  const std::int64_t m = o->m;
  const std::int64_t begin = std::max(from, 2 * m);
  // Indices into the block: a = S_t, b = S_{t-m}, c = S_{t-2m}.
  const std::int64_t first = begin - first_;
  const std::int64_t last = to - first_;
  // The sums in a local: another thread may be writing the next octave's, beside them in memory.
  Sums sums = o->sums;
  // Partial sums over the block (vectorised), then one compensated addition per block.
  const double block = BlockSquares()(hi, lo, first, last, m);
  CompensatedAdd(&sums.o_sum, &sums.o_comp, block);
  sums.o_terms += to - begin + 1;
  // m = 1 and 2 have theirs summed as the prefix sums are made (Add).
  for (std::int64_t t = m <= short_nonoverlap_ ? to + 1 : (begin + m - 1) / m * m; t <= to; t += m) {
    const std::int64_t a = t - first_;
    const double d =
        SecondDifference(hi[a], lo[a], hi[a - m], lo[a - m], hi[a - 2 * m], lo[a - 2 * m]);
    CompensatedAdd(&sums.n_sum, &sums.n_comp, d * d);
    ++sums.n_terms;
  }
  o->sums = sums;
}

void StreamingAvar::FoldStrided(std::int64_t from, std::int64_t to) {
  const std::int64_t first_strided_start = 2 * exact_.back().m;
  if (octaves_.empty() && exact_.back().m <= std::numeric_limits<std::int64_t>::max() / 4 &&
      first_strided_start >= from && first_strided_start <= to) {
    StartNextOctave();
  }
  // Octaves may be added inside the loop: index, not iterators or references.
  for (std::size_t j = 0; j < octaves_.size(); ++j) {
    const std::int64_t first = octaves_[j].last_index + octaves_[j].stride;
    const std::int64_t seed_at = 2 * octaves_[j].m;  // the next octave starts from this ring
    if (j + 1 == octaves_.size() && first <= seed_at && seed_at <= to) {
      PushRun(&octaves_[j], first, seed_at);
      StartNextOctave();
    }
    PushRun(&octaves_[j], octaves_[j].last_index + octaves_[j].stride, to);
  }
}

void StreamingAvar::Fold() {
  const std::int64_t from = folded_ + 1;
  const std::int64_t to = n_;
  if (from > to) return;
  // Each exact octave with a term (2m <= to) is a piece, and the strided octaves together are
  // one more (each starts from the one before it): pieces with sums of their own, which read the
  // block and write nothing else, so two threads may share them.
  std::size_t active = 0;
  while (active < exact_.size() && 2 * exact_[active].m <= to) ++active;
  const auto fold_piece = [&](int piece) {
    const auto p = static_cast<std::size_t>(piece);
    if (p < active) {
      FoldExact(&exact_[p], from, to);
    } else {
      FoldStrided(from, to);
    }
  };
  const int pieces = static_cast<int>(active) + 1;
  if (sharing_ && to - from + 1 >= kSharedFoldValues) {
    sharing_->Run(pieces, fold_piece);
  } else {
    for (int p = 0; p < pieces; ++p) fold_piece(p);
  }
  folded_ = to;
  // Keep S_{to - 2 largest} .. S_to for the next block's lags.
  const std::int64_t held = to - first_ + 1;
  const auto keep = static_cast<std::int64_t>(kept_);
  if (held > keep) {
    const std::int64_t drop = held - keep;
    std::copy(hi_.begin() + drop, hi_.end(), hi_.begin());
    std::copy(lo_.begin() + drop, lo_.end(), lo_.begin());
    hi_.resize(static_cast<std::size_t>(keep));
    lo_.resize(static_cast<std::size_t>(keep));
    first_ += drop;
  }
}

void StreamingAvar::Add(double y) { Add(std::span<const double>(&y, 1)); }

void StreamingAvar::Add(std::span<const double> y) {
  if (y.empty()) return;
  if (n_ == 0) reference_ = y.front();
  // The prefix sum in locals, so that the chain of dependent additions each sample waits on stays
  // in registers (a member would be stored and loaded again on every sample).
  double hi = prefix_.hi, lo = prefix_.lo;
  const double reference = reference_;
  // The non-overlapping sums of m = 1 and 2 are summed here, term by term in the order Fold
  // would sum them: their own chains of additions run beside the prefix sum's, which leaves the
  // core idle most of each sample, instead of in a loop of their own.
  const bool has_m1 = short_nonoverlap_ >= 1, has_m2 = short_nonoverlap_ >= 2;
  Sums s1 = has_m1 ? exact_[0].sums : Sums{};
  Sums s2 = has_m2 ? exact_[1].sums : Sums{};
  std::size_t i = 0;
  while (i < y.size()) {
    const std::size_t start = hi_.size();
    const std::size_t run = std::min(capacity_ - start, y.size() - i);
    hi_.resize(start + run);
    lo_.resize(start + run);
    double* const h = hi_.data();
    double* const l = lo_.data();
    std::int64_t n = n_;  // index of the prefix sum written last
    for (std::size_t k = 0; k < run; ++k) {
      const double x = y[i + k] - reference;
      // (hi, lo) += x in double-double: the exact error of hi + x, then renormalise. When
      // |hi| >= |x|, as for nearly every sample once the sum has grown, Dekker's FastTwoSum
      // gives that error in two operations; Knuth's TwoSum, for the rest, in five. Both give it
      // exactly, so the same bits: the branch only shortens the chain.
      const double t = hi + x;
      double err;
      if (__builtin_expect(std::abs(hi) >= std::abs(x), 1)) {
        err = x - (t - hi);
      } else {
        const double bp = t - hi;
        err = (hi - (t - bp)) + (x - bp);
      }
      const double sum_lo = lo + err;
      hi = t + sum_lo;
      lo = sum_lo - (hi - t);
      const std::size_t j = start + k;
      h[j] = hi;
      l[j] = lo;
      ++n;
      if (has_m1 && n >= 2) {
        const double d = SecondDifference(hi, lo, h[j - 1], l[j - 1], h[j - 2], l[j - 2]);
        CompensatedAdd(&s1.n_sum, &s1.n_comp, d * d);
        ++s1.n_terms;
      }
      if (has_m2 && (n & 1) == 0 && n >= 4) {
        const double d = SecondDifference(hi, lo, h[j - 2], l[j - 2], h[j - 4], l[j - 4]);
        CompensatedAdd(&s2.n_sum, &s2.n_comp, d * d);
        ++s2.n_terms;
      }
    }
    i += run;
    n_ += static_cast<std::int64_t>(run);
    prefix_ = {hi, lo};
    if (has_m1) exact_[0].sums = s1;
    if (has_m2) exact_[1].sums = s2;
    if (hi_.size() == capacity_) {
      Fold();
      if (has_m1) s1 = exact_[0].sums;
      if (has_m2) s2 = exact_[1].sums;
    }
  }
}

std::vector<StreamingAvarPoint> StreamingAvar::Points() const {
  if (folded_ < n_) {
    StreamingAvar folded = *this;
    folded.Fold();
    return folded.Points();
  }
  std::vector<StreamingAvarPoint> points;
  const auto point = [this](std::int64_t m, std::int64_t stride, const Sums& s) {
    StreamingAvarPoint p;
    p.m = m;
    const double denominator = 2.0 * static_cast<double>(m) * static_cast<double>(m);
    p.overlapping = (s.o_sum + s.o_comp) / (denominator * static_cast<double>(s.o_terms));
    p.overlapping_terms = s.o_terms;
    p.overlapping_stride = stride;
    p.nonoverlapping = (s.n_sum + s.n_comp) / (denominator * static_cast<double>(s.n_terms));
    p.nonoverlapping_terms = s.n_terms;
    return p;
  };
  for (const ExactOctave& o : exact_) {
    if (n_ < 2 * o.m) return points;
    points.push_back(point(o.m, 1, o.sums));
  }
  for (const Octave& o : octaves_) {
    if (n_ < 2 * o.m) break;
    points.push_back(point(o.m, o.stride, o.sums));
  }
  return points;
}

std::size_t StreamingAvar::StateBytes() const {
  std::size_t bytes = sizeof *this + (hi_.capacity() + lo_.capacity()) * sizeof(double) +
                      exact_.capacity() * sizeof(ExactOctave) +
                      octaves_.capacity() * sizeof(Octave);
  for (const Octave& o : octaves_) bytes += o.ring.capacity() * sizeof(DoubleDouble);
  return bytes;
}

}  // namespace allanlab::estimators
