#pragma once
// Allan variance of a rate record read once, front to back, in memory that does not grow with
// the record (for files larger than memory: `allanlab avar --stream`).
//
// What it computes, for every octave m = 2^j with N >= 2m (N = samples added), with
// S_n = y_0 + ... + y_{n-1} and the second difference D(t, m) = S_{t+2m} - 2 S_{t+m} + S_t
// (= m (ybar_{t+m} - ybar_t), the same quantity as estimators/allan_variance.h):
//  - non-overlapping AVAR (IEEE 952 Annex C): sum over t = 0, m, 2m, ..., t + 2m <= N of
//    D^2 / (2 m^2 T), T = floor(N/m) - 1 terms. Exactly AllanVariance(kNonOverlapping).
//  - overlapping AVAR over the window starts t = 0, s, 2s, ..., t + 2m <= N, with stride
//    s = max(1, m / exact_overlap_max_m), T = floor((N - 2m)/s) + 1 terms. For
//    m <= exact_overlap_max_m, s = 1: exactly AllanVariance(kOverlapping) (every start). Above
//    it the starts thin out to exact_overlap_max_m per m samples: still an overlapping estimator
//    (each window overlaps the next by 1 - 1/exact_overlap_max_m), with a variance negligibly
//    above the fully overlapping one's, but not the same number. Points say which stride they
//    used.
//
// Why bounded state: the lag-m term S_t S_{t+m} of D^2 needs, in one pass, the prefix sums of the
// last 2m samples at the resolution of the starts, 2 m / s + 1 values: at most
// 2 exact_overlap_max_m + 1 per octave, whatever N. So the state is O(exact_overlap_max_m log N)
// (about 0.5 MiB per octave above 2^14 at the default), and exact overlapping AVAR for every m
// would need O(N) (no one-pass method can do better: the lag-m sum needs the last m values).
// The octaves with every start (stride 1) share one array: the last 2 exact_overlap_max_m + 1
// prefix sums and a block of new ones, folded into every such octave a block at a time (a loop
// over contiguous memory the compiler vectorises: ~1 s for 1e8 samples instead of ~20 s term by
// term). The first strided octave is seeded from that array when it has seen its first 2m
// samples; each later one from its predecessor's ring (every other entry): the decimate-by-2
// cascade. A full block is folded once the next block's samples are in, by a helper thread: the
// caller meanwhile makes the next block's prefix sums (one dependent addition per sample, and the
// short lags' terms from registers), reads the block after it, and then takes the
// fold's pieces the helper has not started (common/piece_sharing.h: Start, Finish).
//
// Precision: the first sample is subtracted (AVAR does not see a constant) and the prefix sum is
// kept as a plain running sum hi plus the sum lo of the exact rounding errors of its additions
// (cascaded summation: hi alone may drift from the sum by up to n u |S| for n samples, u = 2^-53;
// hi + lo only by lo's own rounding, at most n^2 u^2 |S|), so a large bias or drift does not eat
// the digits of the differences (tested with S ~ 2e11 against differences ~1); squared
// differences are summed with Neumaier compensation.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace allanlab {
class PieceSharing;
}

namespace allanlab::estimators {

struct StreamingAvarOptions {
  // Largest m at which the overlapping AVAR uses every start (a power of two >= 1). The state
  // grows with it: (2 exact_overlap_max_m + 1) * 16 bytes per octave at most.
  std::int64_t exact_overlap_max_m = std::int64_t{1} << 14;

  bool IsValid(std::string* why) const;
};

struct StreamingAvarPoint {
  std::int64_t m = 0;        // averaging factor 2^j
  double overlapping = 0.0;  // OAVAR, squared input units
  std::int64_t overlapping_terms = 0;
  std::int64_t overlapping_stride = 1;  // s: 1 means every start (exact OAVAR)
  double nonoverlapping = 0.0;          // AVAR, squared input units
  std::int64_t nonoverlapping_terms = 0;
};

class StreamingAvar {
 public:
  // `options` must be valid (IsValid); an invalid value is replaced by the default.
  explicit StreamingAvar(StreamingAvarOptions options = {});
  // Blocks the prefix-sum buffer holds beyond the kept ones: those are moved to its front once per
  // kRoomBlocks - 1 blocks (it was 2 x 16 bytes copied per new value, every block). At least 4:
  // the window being folded, at the end, and the next one, at the front, must not meet.
  static constexpr std::size_t kRoomBlocks = 4;

  // A fold may be running in the helper (FoldWhileExtending): it is finished before the state
  // goes, and before a copy is made of it (Helper).
  ~StreamingAvar() { FinishFold(); }
  StreamingAvar(const StreamingAvar&) = default;
  StreamingAvar& operator=(const StreamingAvar&) = default;

  // The next rate sample (finite: a NaN would poison every octave; the reader drops them).
  void Add(double y);
  // The next samples, in order: the same as Add for each.
  void Add(std::span<const double> y);

  std::int64_t count() const { return n_ + static_cast<std::int64_t>(pending_.size()); }
  // Every octave m = 2^j with count() >= 2m, ascending.
  std::vector<StreamingAvarPoint> Points() const;
  // Bytes held by the state (the prefix-sum blocks, the samples gathered for the next block and
  // the rings), for memory checks.
  std::size_t StateBytes() const;

 private:
  // An unevaluated sum hi + lo: hi a running sum in plain arithmetic, lo the sum of the exact
  // errors of its additions (not renormalised: |lo| grows like sqrt(n) ulp(hi) for n additions).
  struct DoubleDouble {
    double hi = 0.0, lo = 0.0;
  };
  // Sums of D^2 over the octave's starts (Neumaier compensated).
  struct Sums {
    double o_sum = 0.0, o_comp = 0.0;  // over overlapping starts
    std::int64_t o_terms = 0;
    double n_sum = 0.0, n_comp = 0.0;  // over non-overlapping starts
    std::int64_t n_terms = 0;
  };
  // An octave with every start (m <= exact_overlap_max_m): its terms come from the shared block.
  struct ExactOctave {
    std::int64_t m = 0;
    Sums sums;
  };
  // An octave with strided starts: its own ring of prefix sums at multiples of the stride.
  struct Octave {
    std::int64_t m = 0;
    std::int64_t stride = 1;
    std::int64_t span = 0;           // m / stride: ring positions between t and t + m
    std::vector<DoubleDouble> ring;  // 2 span + 1 prefix sums at multiples of stride
    std::int64_t pushed = 0;         // prefix sums pushed so far
    std::int64_t head = 0;           // ring position of the next push
    std::int64_t last_index = 0;     // sample index n of the latest push
    Sums sums;
    const DoubleDouble& Back(std::int64_t k) const;  // k-th latest pushed value (0 = latest)
  };
  // The prefix sums a fold reads: S_t at hi[t - first], lo[t - first]. A fold in flight keeps its
  // view while the next block's prefix sums are written beyond it or at the buffer's front.
  struct Window {
    const double* hi = nullptr;
    const double* lo = nullptr;
    std::int64_t first = 0;
    DoubleDouble At(std::int64_t n) const {
      return {hi[n - first], lo[n - first]};
    }
  };
  Window Current() const { return {buf_.hi.data() + buf_.base, buf_.lo.data() + buf_.base, first_}; }
  void Push(Octave* o, const DoubleDouble& s, std::int64_t n);
  // Push of S_t for t = t_first, t_first + stride, ... <= t_last (held in the window).
  void PushRun(const Window& w, Octave* o, std::int64_t t_first, std::int64_t t_last);
  void StartNextOctave(const Window& w);
  // One fold of S_from .. S_to into every octave, cut into pieces with sums of their own, which
  // read the window and write nothing else, so two threads may share them: the strided octaves
  // together (piece 0, the longest: each starts from the one before it), then each exact octave
  // with a term, those whose first term is in an earlier block (2m < from) in pairs m and 2m
  // (FoldExactPair: one piece each pair). The octaves' sums are the same whoever runs a piece.
  struct FoldPlan {
    Window window;
    std::int64_t from = 0, to = 0;
    std::size_t active = 0, pairs = 0;
    int pieces = 0;
  };
  FoldPlan PlanFold() const;
  void FoldPiece(const FoldPlan& plan, int piece);
  // Folds the prefix sums S_{folded_ + 1} .. S_{n_} into every octave and keeps the last
  // 2 exact_overlap_max_m + 1 of them for the next block (in this thread and the helper).
  void Fold();
  // Waits for a fold that FoldWhileExtending started (taking its pieces not yet started).
  void FinishFold() const;
  // Makes the prefix sums of y into h[start ..], S_{n + 1} first, h[start - 1] holding S_n and the
  // ones before it (as far as the m = 2 lag needs); sums the short non-overlapping terms.
  void Extend(std::span<const double> y, double* h, double* l, std::size_t start, std::int64_t n);
  // The window full and a whole block of samples at hand (gathered in pending_, or a caller's span
  // that holds one): starts the window's fold (the helper takes it, see FinishFold), makes the
  // block's prefix sums beyond the window, where the buffer has room (else at its front, after
  // the window's last kept_ values are moved there), and moves the window over them. The caller
  // reads the next block meanwhile: it joins the fold at the next block, or when the points are
  // asked for. The sums are those of Fold then Add.
  void FoldWhileExtending(std::span<const double> samples);
  // How many samples pending_ gathers before TakePending: the window's room, or when it is full a
  // block.
  std::size_t Room() const;
  // Extends the window by pending_ (room permitting), or FoldWhileExtending when it is full.
  void TakePending();
  static constexpr std::int64_t kSharedFoldValues = 4096;
  // Fold's pieces: one exact octave, and the strided octaves (from their rings, in order).
  void FoldExact(const Window& w, ExactOctave* o, std::int64_t from, std::int64_t to) const;
  // The exact octaves m and 2m (`twice`), each with its first term before the block (2m < from),
  // in one pass over the block: the same sums as FoldExact on each.
  void FoldExactPair(const Window& w, ExactOctave* o, ExactOctave* twice, std::int64_t from, std::int64_t to) const;
  // Adds a block's squares (starts begin .. to) and non-overlapping terms to the octave's sums.
  void AddBlockTerms(const Window& w, ExactOctave* o, std::int64_t begin, std::int64_t to, double squares) const;
  void FoldStrided(const Window& w, std::int64_t from, std::int64_t to);

  // Fold's second thread, when one is useful; a copy of the state (Points) shares it. The first
  // member: members are copied in declaration order, so copying it finishes the source's fold in
  // flight before any member that fold writes is copied.
  class Helper {
   public:
    Helper() = default;
    Helper(const Helper& other) : sharing_(other.sharing_) { other.Finish(); }
    Helper& operator=(const Helper& other) {
      other.Finish();
      Finish();
      sharing_ = other.sharing_;
      return *this;
    }
    void Finish() const;
    explicit operator bool() const { return sharing_ != nullptr; }
    PieceSharing* operator->() const { return sharing_.get(); }
    void Make();

   private:
    std::shared_ptr<PieceSharing> sharing_;
  };
  Helper sharing_;
  StreamingAvarOptions options_;
  std::int64_t n_ = 0;
  double reference_ = 0.0;
  DoubleDouble prefix_;
  // S_{first_} .. S_{n_} as high and low parts, at hi[base ..], lo[base ..]: the window, held
  // values, at most capacity_ (history + block). The buffers have room for kRoomBlocks blocks
  // beyond the history and never move while a fold is in flight. A copy holds the window alone
  // (at base 0): the room beyond it is no part of the state (Points folds a copy).
  struct Buffers {
    std::vector<double> hi, lo;
    std::size_t base = 0;
    std::size_t held = 1;
    Buffers() = default;
    Buffers(const Buffers& other);
    Buffers& operator=(const Buffers& other);
    Buffers(Buffers&&) = default;
    Buffers& operator=(Buffers&&) = default;
  };
  Buffers buf_;
  std::int64_t first_ = 0;
  std::int64_t folded_ = 0;  // S up to this index are in every octave's sums
  std::size_t kept_ = 0;      // 2 exact_overlap_max_m + 1: S values a block needs before its own
  std::size_t capacity_ = 0;  // kept_ and a block
  std::vector<ExactOctave> exact_;
  // Exact octaves m <= this (at most 2) have their non-overlapping sums made in Extend, beside
  // the prefix sums, into short_sums_, not in Fold.
  std::int64_t short_nonoverlap_ = 0;
  Sums short_sums_[2];
  // Samples gathered while the window is full.
  std::vector<double> pending_;
  std::vector<Octave> octaves_;  // strided, ascending m
};

}  // namespace allanlab::estimators
