#include "estimators/phase_checkpoints.h"

#include <algorithm>

#include "estimators/phase_integral.h"

namespace allanlab::estimators {
namespace {

// Samples integrated per step of the pass that keeps the checkpoints: a buffer that stays in L1.
constexpr std::int64_t kPassPiece = 64 * PhaseCheckpoints::kStride;
static_assert(PhaseCheckpoints::kStride % 8 == 0, "pieces must start at multiples of 8");

}  // namespace

PhaseCheckpoints::PhaseCheckpoints(std::span<const double> rate, double reference)
    : PhaseCheckpoints(rate, reference, Deferred{}) {
  IntegrateUpTo(n_);
}

PhaseCheckpoints::PhaseCheckpoints(std::span<const double> rate, double reference, Deferred)
    : rate_(rate), reference_(reference), n_(static_cast<std::int64_t>(rate.size())) {
  x_.resize(static_cast<std::size_t>(n_ / kStride + 1));
  x_[0] = 0.0;
}

void PhaseCheckpoints::IntegrateUpTo(std::int64_t upto) {
  upto = upto >= n_ ? n_ : upto / kStride * kStride;
  double piece[kPassPiece + 1];
  piece[0] = last_;
  for (std::int64_t lo = done_; lo < upto; lo += kPassPiece) {
    const std::int64_t count = std::min(kPassPiece, upto - lo);
    ContinueIntegral(rate_.subspan(static_cast<std::size_t>(lo), static_cast<std::size_t>(count)), reference_,
                     std::span<double>(piece, static_cast<std::size_t>(count + 1)));
    for (std::int64_t k = kStride; k <= count; k += kStride) {
      x_[static_cast<std::size_t>((lo + k) / kStride)] = piece[k];
    }
    piece[0] = piece[count];
  }
  last_ = piece[0];
  done_ = std::max(done_, upto);
}

double PhaseCheckpoints::At8(std::int64_t a) const {
  const std::int64_t start = a / kStride * kStride;
  if (a == start) return At(start);
  double head[kStride + 1];
  head[0] = At(start);
  ContinueIntegral(rate_.subspan(static_cast<std::size_t>(start), static_cast<std::size_t>(a - start)),
                   reference_, std::span<double>(head, static_cast<std::size_t>(a - start + 1)));
  return head[a - start];
}

void PhaseCheckpoints::Group(std::int64_t a, double x_a, double* group) const {
  const std::int64_t count = std::min<std::int64_t>(8, n_ - a);
  group[0] = x_a;
  ContinueIntegral(rate_.subspan(static_cast<std::size_t>(a), static_cast<std::size_t>(count)), reference_,
                   std::span<double>(group, static_cast<std::size_t>(count + 1)));
}

// Whole groups of 8 from a multiple of 8 are integrated straight into out; a stretch that starts
// or ends inside a group takes that group from a small buffer, integrated whole as the pass
// integrated it (a group's values depend on how it is split: phase_integral.h).
void PhaseCheckpoints::Rebuild(std::int64_t lo, std::span<double> out) const {
  if (out.empty()) return;
  const std::int64_t hi = lo + static_cast<std::int64_t>(out.size()) - 1;
  const auto at = [&](std::int64_t k) -> double& { return out[static_cast<std::size_t>(k - lo)]; };
  std::int64_t a = lo / 8 * 8;
  double group[9];
  if (a < lo) {
    Group(a, At8(a), group);
    for (std::int64_t k = lo; k <= std::min(hi, a + 8); ++k) at(k) = group[k - a];
    a += 8;
    if (a >= hi) return;
  } else {
    at(lo) = At8(lo);
  }
  const std::int64_t body_end = hi == n_ ? n_ : a + (hi - a) / 8 * 8;
  if (body_end > a) {
    ContinueIntegral(rate_.subspan(static_cast<std::size_t>(a), static_cast<std::size_t>(body_end - a)),
                     reference_, out.subspan(static_cast<std::size_t>(a - lo), static_cast<std::size_t>(body_end - a + 1)));
  }
  if (body_end >= hi) return;
  Group(body_end, at(body_end), group);
  for (std::int64_t k = body_end + 1; k <= hi; ++k) at(k) = group[k - body_end];
}

void PhaseCheckpoints::Decimate(std::int64_t first, std::int64_t m, std::span<double> out) const {
  if (m % kStride == 0 && first % kStride == 0) {
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = At(first + static_cast<std::int64_t>(i) * m);
    return;
  }
  // Rebuilt a checkpoint-aligned piece at a time (a few thousand samples), every m-th value kept.
  constexpr std::int64_t kPiece = 64 * kStride;
  std::vector<double> piece(static_cast<std::size_t>(kPiece + 1));
  const std::int64_t last = first + (static_cast<std::int64_t>(out.size()) - 1) * m;
  std::size_t i = 0;
  for (std::int64_t lo = first / kStride * kStride; i < out.size(); lo += kPiece) {
    const std::int64_t hi = std::min(last, lo + kPiece);
    const std::span<double> here = std::span<double>(piece).first(static_cast<std::size_t>(hi - lo + 1));
    Rebuild(lo, here);
    for (; i < out.size(); ++i) {
      const std::int64_t k = first + static_cast<std::int64_t>(i) * m;
      if (k > hi) break;
      out[i] = here[static_cast<std::size_t>(k - lo)];
    }
  }
}

}  // namespace allanlab::estimators
