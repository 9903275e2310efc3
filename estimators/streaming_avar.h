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
// Octave j+1 starts when octave j has seen its first 2m samples, seeded from octave j's ring
// (every other entry once the stride grows): the decimate-by-2 cascade.
//
// Precision: the first sample is subtracted (AVAR does not see a constant) and the prefix sum is
// kept in double-double, so a large bias or drift does not eat the digits of the differences;
// squared differences are summed with Neumaier compensation.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

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

  // The next rate sample (finite: a NaN would poison every octave; the reader drops them).
  void Add(double y);

  std::int64_t count() const { return n_; }
  // Every octave m = 2^j with count() >= 2m, ascending.
  std::vector<StreamingAvarPoint> Points() const;
  // Bytes held by the state (the rings), for memory checks.
  std::size_t StateBytes() const;

 private:
  // An unevaluated sum hi + lo, |lo| <= ulp(hi) / 2.
  struct DoubleDouble {
    double hi = 0.0, lo = 0.0;
  };
  struct Octave {
    std::int64_t m = 0;
    std::int64_t stride = 1;
    std::int64_t span = 0;             // m / stride: ring positions between t and t + m
    std::vector<DoubleDouble> ring;    // 2 span + 1 prefix sums at multiples of stride
    std::int64_t pushed = 0;           // prefix sums pushed so far
    std::int64_t head = 0;             // ring position of the next push
    double o_sum = 0.0, o_comp = 0.0;  // Neumaier sum of D^2 over overlapping starts
    std::int64_t o_terms = 0;
    double n_sum = 0.0, n_comp = 0.0;  // the same over non-overlapping starts
    std::int64_t n_terms = 0;
    const DoubleDouble& Back(std::int64_t k) const;  // k-th latest pushed value (0 = latest)
  };
  void Push(Octave* o, const DoubleDouble& s, std::int64_t n);
  void StartNextOctave();

  StreamingAvarOptions options_;
  std::int64_t n_ = 0;
  double reference_ = 0.0;
  DoubleDouble prefix_;
  std::vector<Octave> octaves_;
};

}  // namespace allanlab::estimators
