#include "estimators/streaming_avar.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <functional>
#include <limits>

#include "common/cpu_features.h"
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

// D at lag m from S_a, S_{a-m}, S_{a-2m} in the block.
__attribute__((always_inline)) inline double LagDifference(const double* hi, const double* lo,
                                                           std::int64_t a, std::int64_t m) {
  return SecondDifference(hi[a], lo[a], hi[a - m], lo[a - m], hi[a - 2 * m], lo[a - 2 * m]);
}

// Adds D^2 at lags m and 2m (ms[0] and ms[1], when pair; lag m alone otherwise) for the block
// indices a = first .. end - 1 ((end - first) a multiple of 8) to eight partial sums per lag,
// lanes[k] taking every eighth index from first + k. A block's squares at one lag are these
// groups, then its last (count mod 8) terms added to lanes[0], then the lanes added in a fixed
// order (LaneTotal): every version below gives the same bits, whatever vector width the
// compiler uses for the eight lanes. The two lags share S_a and S_{a-2m}: one pass loads four
// values per index for two terms instead of six for each, and loads are what bounds this loop.
template <bool kPair>
__attribute__((always_inline)) inline void GroupsBody(const double* hi, const double* lo,
                                                      std::int64_t first, std::int64_t end,
                                                      std::int64_t m, double* lanes_m,
                                                      double* lanes_2m) {
  double l1[8], l2[8];
  for (int k = 0; k < 8; ++k) {
    l1[k] = lanes_m[k];
    l2[k] = kPair ? lanes_2m[k] : 0.0;
  }
  for (std::int64_t i = first; i + 8 <= end; i += 8) {
    for (int k = 0; k < 8; ++k) {
      const std::int64_t a = i + k;
      const double a_hi = hi[a], a_lo = lo[a];
      const double b_hi = hi[a - m], b_lo = lo[a - m];
      const double c_hi = hi[a - 2 * m], c_lo = lo[a - 2 * m];
      const double d = SecondDifference(a_hi, a_lo, b_hi, b_lo, c_hi, c_lo);
      l1[k] += d * d;
      if constexpr (kPair) {
        const double e = SecondDifference(a_hi, a_lo, c_hi, c_lo, hi[a - 4 * m], lo[a - 4 * m]);
        l2[k] += e * e;
      }
    }
  }
  for (int k = 0; k < 8; ++k) {
    lanes_m[k] = l1[k];
    if (kPair) lanes_2m[k] = l2[k];
  }
}

// The last (count mod 8) terms, first .. last, into lanes[0]; then the total of the lanes.
double LaneTotal(const double* hi, const double* lo, std::int64_t first, std::int64_t last,
                 std::int64_t m, double* lanes) {
  for (std::int64_t i = first; i <= last; ++i) {
    const double d = LagDifference(hi, lo, i, m);
    lanes[0] += d * d;
  }
  return ((lanes[0] + lanes[1]) + (lanes[2] + lanes[3])) +
         ((lanes[4] + lanes[5]) + (lanes[6] + lanes[7]));
}

using GroupsFn = void (*)(const double*, const double*, std::int64_t, std::int64_t, std::int64_t,
                          double*, double*);

template <bool kPair>
void PortableGroups(const double* hi, const double* lo, std::int64_t first, std::int64_t end,
                    std::int64_t m, double* lanes_m, double* lanes_2m) {
  GroupsBody<kPair>(hi, lo, first, end, m, lanes_m, lanes_2m);
}

#if defined(__x86_64__) && defined(__GNUC__)
// No FMA: a fused d * d + lane would round differently from the portable version.
template <bool kPair>
__attribute__((target("avx2"))) void Avx2Groups(const double* hi, const double* lo,
                                                std::int64_t first, std::int64_t end,
                                                std::int64_t m, double* lanes_m,
                                                double* lanes_2m) {
  GroupsBody<kPair>(hi, lo, first, end, m, lanes_m, lanes_2m);
}
#endif

// The squares of one lag (pair false) or of the lags m and 2m (pair true).
GroupsFn BlockGroups(bool pair) {
#if defined(__x86_64__) && defined(__GNUC__)
  if (CpuHasAvx2()) return pair ? Avx2Groups<true> : Avx2Groups<false>;
#endif
  return pair ? PortableGroups<true> : PortableGroups<false>;
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
  buf_.hi.reserve(reserved);
  buf_.lo.reserve(reserved);
  buf_.hi.push_back(0.0);  // S_0
  buf_.lo.push_back(0.0);
  buf_.held = 1;
  short_nonoverlap_ = std::min<std::int64_t>(largest, 2);
  if (PieceSharing::Useful()) sharing_.Make();
}

StreamingAvar::Buffers::Buffers(const Buffers& other)
    : hi(other.hi.begin() + static_cast<std::ptrdiff_t>(other.base),
         other.hi.begin() + static_cast<std::ptrdiff_t>(other.base + other.held)),
      lo(other.lo.begin() + static_cast<std::ptrdiff_t>(other.base),
         other.lo.begin() + static_cast<std::ptrdiff_t>(other.base + other.held)),
      held(other.held) {}

StreamingAvar::Buffers& StreamingAvar::Buffers::operator=(const Buffers& other) {
  if (this != &other) *this = Buffers(other);
  return *this;
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

void StreamingAvar::PushRun(const Window& w, Octave* o, std::int64_t t_first, std::int64_t t_last) {
  const std::int64_t stride = o->stride;
  std::int64_t t = t_first;
  // Until the ring is full a push makes no term: these go one at a time (once per octave).
  for (; t <= t_last && o->pushed + 1 < 2 * o->span + 1; t += stride) Push(o, w.At(t), t);
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
  const double* const hi = w.hi;
  const double* const lo = w.lo;
  std::int64_t pushes = 0;
  while (t <= t_last) {
    // A run of pushes in which no ring position wraps and none but the last can start a
    // non-overlapping term (t a multiple of m; t is a multiple of the stride, which divides m):
    // those go through a loop without either check, a third fewer instructions per push.
    const std::int64_t left = (t_last - t) / stride + 1;
    const std::int64_t to_start = ((-t) & m_mask) / stride + 1;
    const std::int64_t run = std::min({left, to_start, size - h, size - b, size - c});
    for (std::int64_t k = 1; k < run; ++k, t += stride) {
      const auto i = static_cast<std::size_t>(t - w.first);
      const double a_hi = hi[i], a_lo = lo[i];
      ring[h] = {a_hi, a_lo};
      const double d = SecondDifference(a_hi, a_lo, ring[b].hi, ring[b].lo, ring[c].hi, ring[c].lo);
      CompensatedAdd(&sums.o_sum, &sums.o_comp, d * d);
      ++h;
      ++b;
      ++c;
    }
    // The run's last push: it may start a non-overlapping term, and a position may wrap after it.
    const auto i = static_cast<std::size_t>(t - w.first);
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
    t += stride;
    pushes += run;
  }
  sums.o_terms += pushes;
  o->sums = sums;
  o->head = h;
  o->pushed += pushes;
  o->last_index = t - stride;
}

void StreamingAvar::StartNextOctave(const Window& w) {
  Octave next;
  if (octaves_.empty()) {
    // The first strided octave: the block still holds S_0 .. S_{next.m}.
    next.m = 2 * exact_.back().m;
    next.stride = 2;
    next.span = next.m / next.stride;
    next.ring.resize(static_cast<std::size_t>(2 * next.span + 1));
    for (std::int64_t k = 0; k <= next.m; k += next.stride) Push(&next, w.At(k), k);
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

void StreamingAvar::FoldExact(const Window& w, ExactOctave* o, std::int64_t from, std::int64_t to) const {
  const std::int64_t m = o->m;
  const std::int64_t begin = std::max(from, 2 * m);
  // Indices into the window: a = S_t, b = S_{t-m}, c = S_{t-2m}.
  const std::int64_t first = begin - w.first;
  const std::int64_t last = to - w.first;
  const std::int64_t end = first + (last - first + 1) / 8 * 8;
  double lanes[8] = {};
  BlockGroups(false)(w.hi, w.lo, first, end, m, lanes, nullptr);
  AddBlockTerms(w, o, begin, to, LaneTotal(w.hi, w.lo, end, last, m, lanes));
}

void StreamingAvar::FoldExactPair(const Window& w, ExactOctave* o, ExactOctave* twice, std::int64_t from,
                                  std::int64_t to) const {
  const std::int64_t m = o->m;
  const std::int64_t first = from - w.first;
  const std::int64_t last = to - w.first;
  const std::int64_t end = first + (last - first + 1) / 8 * 8;
  double lanes_m[8] = {}, lanes_2m[8] = {};
  BlockGroups(true)(w.hi, w.lo, first, end, m, lanes_m, lanes_2m);
  AddBlockTerms(w, o, from, to, LaneTotal(w.hi, w.lo, end, last, m, lanes_m));
  AddBlockTerms(w, twice, from, to, LaneTotal(w.hi, w.lo, end, last, 2 * m, lanes_2m));
}

void StreamingAvar::AddBlockTerms(const Window& w, ExactOctave* o, std::int64_t begin, std::int64_t to,
                                  double squares) const {
  const double* hi = w.hi;
  const double* lo = w.lo;
  const std::int64_t m = o->m;
  // The sums in a local: another thread may be writing the next octave's, beside them in memory.
  Sums sums = o->sums;
  // The block's partial sums (vectorised), one compensated addition per block.
  CompensatedAdd(&sums.o_sum, &sums.o_comp, squares);
  sums.o_terms += to - begin + 1;
  // m = 1 and 2 have theirs summed as the prefix sums are made (Extend).
  for (std::int64_t t = m <= short_nonoverlap_ ? to + 1 : (begin + m - 1) / m * m; t <= to; t += m) {
    const std::int64_t a = t - w.first;
    const double d =
        SecondDifference(hi[a], lo[a], hi[a - m], lo[a - m], hi[a - 2 * m], lo[a - 2 * m]);
    CompensatedAdd(&sums.n_sum, &sums.n_comp, d * d);
    ++sums.n_terms;
  }
  o->sums = sums;
}

void StreamingAvar::FoldStrided(const Window& w, std::int64_t from, std::int64_t to) {
  const std::int64_t first_strided_start = 2 * exact_.back().m;
  if (octaves_.empty() && exact_.back().m <= std::numeric_limits<std::int64_t>::max() / 4 &&
      first_strided_start >= from && first_strided_start <= to) {
    StartNextOctave(w);
  }
  // Octaves may be added inside the loop: index, not iterators or references.
  for (std::size_t j = 0; j < octaves_.size(); ++j) {
    const std::int64_t first = octaves_[j].last_index + octaves_[j].stride;
    const std::int64_t seed_at = 2 * octaves_[j].m;  // the next octave starts from this ring
    if (j + 1 == octaves_.size() && first <= seed_at && seed_at <= to) {
      PushRun(w, &octaves_[j], first, seed_at);
      StartNextOctave(w);
    }
    PushRun(w, &octaves_[j], octaves_[j].last_index + octaves_[j].stride, to);
  }
}

StreamingAvar::FoldPlan StreamingAvar::PlanFold() const {
  FoldPlan plan;
  plan.window = Current();
  plan.from = folded_ + 1;
  plan.to = n_;
  if (plan.from > plan.to) return plan;
  while (plan.active < exact_.size() && 2 * exact_[plan.active].m <= plan.to) ++plan.active;
  std::size_t settled = 0;
  while (settled < plan.active && 2 * exact_[settled].m < plan.from) ++settled;
  plan.pairs = settled / 2;
  plan.pieces = 1 + static_cast<int>(plan.active - plan.pairs);
  return plan;
}

void StreamingAvar::FoldPiece(const FoldPlan& plan, int piece) {
  if (piece == 0) {
    FoldStrided(plan.window, plan.from, plan.to);
    return;
  }
  const auto q = static_cast<std::size_t>(piece - 1);
  if (q < plan.pairs) {
    FoldExactPair(plan.window, &exact_[2 * q], &exact_[2 * q + 1], plan.from, plan.to);
  } else {
    FoldExact(plan.window, &exact_[q + plan.pairs], plan.from, plan.to);  // the octaves after the pairs'
  }
}

void StreamingAvar::Fold() {
  FinishFold();
  const FoldPlan plan = PlanFold();
  if (plan.pieces == 0) return;
  const auto piece = [&](int p) { FoldPiece(plan, p); };
  if (sharing_ && plan.to - plan.from + 1 >= kSharedFoldValues) {
    sharing_->Run(plan.pieces, piece);
  } else {
    for (int p = 0; p < plan.pieces; ++p) piece(p);
  }
  folded_ = plan.to;
  // Keep S_{to - 2 largest} .. S_to for the next block's lags, at the front of the buffer.
  const auto keep = std::min(buf_.held, kept_);
  const std::size_t drop = buf_.held - keep;
  if (buf_.base + drop > 0) {
    std::copy(buf_.hi.begin() + static_cast<std::ptrdiff_t>(buf_.base + drop),
              buf_.hi.begin() + static_cast<std::ptrdiff_t>(buf_.base + buf_.held), buf_.hi.begin());
    std::copy(buf_.lo.begin() + static_cast<std::ptrdiff_t>(buf_.base + drop),
              buf_.lo.begin() + static_cast<std::ptrdiff_t>(buf_.base + buf_.held), buf_.lo.begin());
  }
  first_ += static_cast<std::int64_t>(drop);
  buf_.base = 0;
  buf_.held = keep;
}

void StreamingAvar::FinishFold() const { sharing_.Finish(); }

void StreamingAvar::Helper::Finish() const {
  if (sharing_) sharing_->Finish();
}

void StreamingAvar::Helper::Make() { sharing_ = std::make_shared<PieceSharing>(); }

// Every sample is gathered first, and its prefix sum made with the others gathered (Extend runs
// over many samples, whichever Add brought them): once there are as many as the buffer has room
// for, or, when the buffer is full, a whole block (then folded while they are extended).
void StreamingAvar::Add(double y) {
  if (n_ == 0 && pending_.empty()) reference_ = y;
  pending_.push_back(y);
  if (pending_.size() == Room()) TakePending();
}

void StreamingAvar::Add(std::span<const double> y) {
  if (y.empty()) return;
  if (n_ == 0 && pending_.empty()) reference_ = y.front();
  while (!y.empty()) {
    if (pending_.empty() && buf_.held == capacity_ && y.size() >= Room()) {
      // A whole block in the caller's span (a raw reader's chunk): used where it lies, not gathered.
      const std::size_t block = Room();
      FoldWhileExtending(y.first(block));
      y = y.subspan(block);
      continue;
    }
    const std::size_t take = std::min(Room() - pending_.size(), y.size());
    pending_.insert(pending_.end(), y.begin(), y.begin() + static_cast<std::ptrdiff_t>(take));
    y = y.subspan(take);
    if (pending_.size() == Room()) TakePending();
  }
}

std::size_t StreamingAvar::Room() const {
  return buf_.held < capacity_ ? capacity_ - buf_.held : capacity_ - kept_;
}

void StreamingAvar::TakePending() {
  if (buf_.held == capacity_) {
    FoldWhileExtending(pending_);
    pending_.clear();
    return;
  }
  // Room in the window (the record's first block, or its last): the prefix sums go straight in.
  FinishFold();  // none is in flight before the first block, but the buffer may move here
  const std::size_t start = buf_.base + buf_.held;
  if (buf_.hi.size() < start + pending_.size()) {
    buf_.hi.resize(start + pending_.size());
    buf_.lo.resize(start + pending_.size());
  }
  Extend(pending_, buf_.hi.data() + buf_.base, buf_.lo.data() + buf_.base, buf_.held, n_);
  buf_.held += pending_.size();
  n_ += static_cast<std::int64_t>(pending_.size());
  pending_.clear();
}

void StreamingAvar::Extend(std::span<const double> y, double* h, double* l, std::size_t start,
                           std::int64_t n) {
  // The prefix sum in locals, so that the chain of dependent additions each sample waits on stays
  // in registers (a member would be stored and loaded again on every sample).
  double hi = prefix_.hi, lo = prefix_.lo;
  const double reference = reference_;
  // The non-overlapping sums of m = 1 and 2 are summed here, term by term in the order Fold
  // would sum them: their own chains of additions run beside the prefix sum's, which leaves the
  // core idle most of each sample, instead of in a loop of their own.
  const bool has_m1 = short_nonoverlap_ >= 1, has_m2 = short_nonoverlap_ >= 2;
  Sums s1 = short_sums_[0], s2 = short_sums_[1];
  // The four prefix sums before the one being made, S_{n-1} .. S_{n-4} once n is its index, in
  // registers: read back from h and l, each lag's load waited on the store just made to the other
  // array at the same address modulo 4096 (the two arrays are page-aligned alike): 1e8 samples
  // took 2.4 s with those loads, 0.89 s without.
  double ph[4] = {}, pl[4] = {};
  for (std::size_t i = 0; i < 4 && i < start && static_cast<std::int64_t>(i) <= n; ++i) {
    ph[i] = h[start - 1 - i];
    pl[i] = l[start - 1 - i];
  }
  for (std::size_t k = 0; k < y.size(); ++k) {
    const double x = y[k] - reference;
    // S = hi + lo, hi the plain running sum and lo the sum of the exact errors of its additions
    // (Knuth's TwoSum: exact whatever the magnitudes). Each of the two is one addition per
    // sample, so the chain every sample waits on is that one addition (~4 cycles); renormalising
    // hi + lo after each sample put five dependent additions on it (~20 cycles).
    const double t = hi + x;
    const double bp = t - hi;
    lo += (hi - (t - bp)) + (x - bp);
    hi = t;
    const std::size_t j = start + k;
    h[j] = hi;
    l[j] = lo;
    ++n;  // index of the prefix sum just written
    if (has_m1 && n >= 2) {
      const double d = SecondDifference(hi, lo, ph[0], pl[0], ph[1], pl[1]);
      CompensatedAdd(&s1.n_sum, &s1.n_comp, d * d);
      ++s1.n_terms;
    }
    if (has_m2 && (n & 1) == 0 && n >= 4) {
      const double d = SecondDifference(hi, lo, ph[1], pl[1], ph[3], pl[3]);
      CompensatedAdd(&s2.n_sum, &s2.n_comp, d * d);
      ++s2.n_terms;
    }
    ph[3] = ph[2], pl[3] = pl[2];
    ph[2] = ph[1], pl[2] = pl[1];
    ph[1] = ph[0], pl[1] = pl[0];
    ph[0] = hi, pl[0] = lo;
  }
  prefix_ = {hi, lo};
  short_sums_[0] = s1;
  short_sums_[1] = s2;
}

void StreamingAvar::FoldWhileExtending(std::span<const double> samples) {
  // The previous block's fold first: its octaves' sums come before this one's, and it may read
  // the memory written below.
  FinishFold();
  const std::size_t block = samples.size();
  const std::size_t room = kept_ + kRoomBlocks * (capacity_ - kept_);
  static_assert(kRoomBlocks >= 4, "the window at the end and the next one at the front must not meet");
  if (buf_.hi.size() < room) {  // sized before any fold reads it
    buf_.hi.resize(room);
    buf_.lo.resize(room);
  }
  // The next window starts with this one's last kept_ prefix sums (the lags its block needs):
  // where they are when the block fits beyond this window, else moved to the front of the
  // buffer, before the fold of this window (at the end of the buffer, clear of the front
  // kept_ + block, since kept_ <= block + 1) starts reading.
  std::size_t next_base = buf_.base + buf_.held - kept_;
  if (next_base + kept_ + block > room) {
    const auto tail = static_cast<std::ptrdiff_t>(buf_.base + buf_.held);
    const auto keep = static_cast<std::ptrdiff_t>(kept_);
    std::copy(buf_.hi.begin() + tail - keep, buf_.hi.begin() + tail, buf_.hi.begin());
    std::copy(buf_.lo.begin() + tail - keep, buf_.lo.begin() + tail, buf_.lo.begin());
    next_base = 0;
  }
  // The fold reads only this window and writes only the octaves' sums, which nothing below
  // touches: with a helper it runs there (this thread joins it at the next block), else now.
  const FoldPlan plan = PlanFold();
  if (sharing_ && plan.to - plan.from + 1 >= kSharedFoldValues) {
    sharing_->Start(plan.pieces, [this, plan](int p) { FoldPiece(plan, p); });
  } else {
    for (int p = 0; p < plan.pieces; ++p) FoldPiece(plan, p);
  }
  folded_ = plan.to;
  Extend(samples, buf_.hi.data() + next_base, buf_.lo.data() + next_base, kept_, n_);
  first_ = n_ + 1 - static_cast<std::int64_t>(kept_);
  n_ += static_cast<std::int64_t>(block);
  buf_.held = kept_ + block;
  buf_.base = next_base;
}

std::vector<StreamingAvarPoint> StreamingAvar::Points() const {
  FinishFold();
  if (folded_ < n_ || !pending_.empty()) {
    StreamingAvar folded = *this;
    folded.Fold();
    // Fewer samples gathered than Room() had before the fold, which the fold did not reduce.
    if (!folded.pending_.empty()) folded.TakePending();
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
  for (std::size_t k = 0; k < exact_.size(); ++k) {
    const ExactOctave& o = exact_[k];
    if (n_ < 2 * o.m) return points;
    Sums sums = o.sums;
    if (o.m <= short_nonoverlap_) {  // its non-overlapping sums were made in Extend
      sums.n_sum = short_sums_[k].n_sum;
      sums.n_comp = short_sums_[k].n_comp;
      sums.n_terms = short_sums_[k].n_terms;
    }
    points.push_back(point(o.m, 1, sums));
  }
  for (const Octave& o : octaves_) {
    if (n_ < 2 * o.m) break;
    points.push_back(point(o.m, o.stride, o.sums));
  }
  return points;
}

std::size_t StreamingAvar::StateBytes() const {
  FinishFold();  // the strided octaves may be growing
  std::size_t bytes = sizeof *this +
                      (buf_.hi.capacity() + buf_.lo.capacity() + pending_.capacity()) * sizeof(double) +
                      exact_.capacity() * sizeof(ExactOctave) +
                      octaves_.capacity() * sizeof(Octave);
  for (const Octave& o : octaves_) bytes += o.ring.capacity() * sizeof(DoubleDouble);
  return bytes;
}

}  // namespace allanlab::estimators
