#include "estimators/streaming_avar.h"

#include <bit>
#include <cmath>

namespace allanlab::estimators {
namespace {

// Neumaier's compensated sum: the lost low part of each addition is kept in *comp.
void CompensatedAdd(double* sum, double* comp, double v) {
  const double t = *sum + v;
  *comp += std::abs(*sum) >= std::abs(v) ? (*sum - t) + v : (v - t) + *sum;
  *sum = t;
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
  Octave first;
  first.m = 1;
  first.stride = 1;
  first.span = 1;
  first.ring.resize(3);
  octaves_.push_back(std::move(first));
  Push(&octaves_.back(), DoubleDouble(), 0);
}

const StreamingAvar::DoubleDouble& StreamingAvar::Octave::Back(std::int64_t k) const {
  std::int64_t index = head - 1 - k;
  if (index < 0) index += static_cast<std::int64_t>(ring.size());
  return ring[static_cast<std::size_t>(index)];
}

void StreamingAvar::Push(Octave* o, const DoubleDouble& s, std::int64_t n) {
  // Ring positions and the power-of-two tests below avoid integer division: this runs for
  // every sample in every octave whose stride is 1.
  o->ring[static_cast<std::size_t>(o->head)] = s;
  if (++o->head == static_cast<std::int64_t>(o->ring.size())) o->head = 0;
  ++o->pushed;
  if (o->pushed < 2 * o->span + 1) return;
  const DoubleDouble& a = o->Back(0);
  const DoubleDouble& b = o->Back(o->span);
  const DoubleDouble& c = o->Back(2 * o->span);
  // Neighbouring prefix sums are close, so the differences of the high parts are exact
  // (Sterbenz) and the low parts carry what the high parts rounded away.
  const double d = ((a.hi - b.hi) - (b.hi - c.hi)) + ((a.lo - b.lo) - (b.lo - c.lo));
  CompensatedAdd(&o->o_sum, &o->o_comp, d * d);
  ++o->o_terms;
  if ((n & (o->m - 1)) == 0) {
    CompensatedAdd(&o->n_sum, &o->n_comp, d * d);
    ++o->n_terms;
  }
}

void StreamingAvar::StartNextOctave() {
  const Octave& last = octaves_.back();
  Octave next;
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

void StreamingAvar::Add(double y) {
  if (n_ == 0) reference_ = y;
  const double x = y - reference_;
  // prefix_ += x in double-double (TwoSum, then renormalise).
  const double t = prefix_.hi + x;
  const double bp = t - prefix_.hi;
  const double err = (prefix_.hi - (t - bp)) + (x - bp);
  const double lo = prefix_.lo + err;
  prefix_.hi = t + lo;
  prefix_.lo = lo - (prefix_.hi - t);
  ++n_;
  for (Octave& o : octaves_) {
    if ((n_ & (o.stride - 1)) == 0) Push(&o, prefix_, n_);
  }
  if (n_ == 2 * octaves_.back().m) StartNextOctave();
}

std::vector<StreamingAvarPoint> StreamingAvar::Points() const {
  std::vector<StreamingAvarPoint> points;
  for (const Octave& o : octaves_) {
    if (n_ < 2 * o.m) break;
    StreamingAvarPoint p;
    p.m = o.m;
    const double denominator = 2.0 * static_cast<double>(o.m) * static_cast<double>(o.m);
    p.overlapping = (o.o_sum + o.o_comp) / (denominator * static_cast<double>(o.o_terms));
    p.overlapping_terms = o.o_terms;
    p.overlapping_stride = o.stride;
    p.nonoverlapping = (o.n_sum + o.n_comp) / (denominator * static_cast<double>(o.n_terms));
    p.nonoverlapping_terms = o.n_terms;
    points.push_back(p);
  }
  return points;
}

std::size_t StreamingAvar::StateBytes() const {
  std::size_t bytes = sizeof *this + octaves_.capacity() * sizeof(Octave);
  for (const Octave& o : octaves_) bytes += o.ring.capacity() * sizeof(DoubleDouble);
  return bytes;
}

}  // namespace allanlab::estimators
