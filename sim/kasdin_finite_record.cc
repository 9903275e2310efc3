#include "sim/kasdin_finite_record.h"

#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include "common/thread_memo.h"

namespace allanlab::sim {
namespace {

// Points summed exactly after each switch-on (distance of the quadrature from the singularity).
constexpr std::int64_t kExact = 128;
// Gregory end corrections c_j = |G_{j+1}| (Gregory coefficients), j = 1..8.
constexpr std::array<double, 8> kGregory = {1.0 / 12.0,         1.0 / 24.0,          19.0 / 720.0,
                                            3.0 / 160.0,        863.0 / 60480.0,     275.0 / 24192.0,
                                            33953.0 / 3628800.0, 8183.0 / 1036800.0};
constexpr int kOrder = static_cast<int>(kGregory.size());

// S(v) for integers v < kExact + 1 by the same recursion and summation as KasdinCoefficients and
// CumulativeSum, so the direct and the fast sums share their small-v values bit for bit.
const std::array<double, kExact + 1>& SmallTable() {
  static const std::array<double, kExact + 1> table = [] {
    std::array<double, kExact + 1> t{};
    double h = 1.0;
    long double acc = 0.0L;
    for (std::size_t k = 0; k < t.size(); ++k) {
      if (k > 0) h = h * (static_cast<double>(k) - 0.5) / static_cast<double>(k);
      t[k] = static_cast<double>(acc += h);
    }
    return t;
  }();
  return table;
}

// 2 Gamma(z + 1/2) / (sqrt(pi) Gamma(z)) for z >= kExact + 1, from
// ln Gamma(z + 1/2) - ln Gamma(z) = ln(z)/2 + sum_{n odd} (2^-n - 2) B_{n+1} / (n (n+1) z^n).
double LargeCumulative(double z) {
  const double r = 1.0 / z, r2 = r * r;
  const double series =
      r * (-1.0 / 8.0 +
           r2 * (1.0 / 192.0 + r2 * (-1.0 / 640.0 + r2 * (17.0 / 14336.0 - r2 * (341.0 / 202752.0)))));
  return 2.0 / std::sqrt(std::numbers::pi) * std::sqrt(z) * std::exp(series);
}

double CumulativeAt(std::int64_t v) {
  if (v < 0) return 0.0;
  if (v <= kExact) return SmallTable()[static_cast<std::size_t>(v)];
  return LargeCumulative(static_cast<double>(v) + 1.0);
}

// 12-point Gauss-Legendre nodes and weights on [-1, 1] (Newton on P_12).
struct GaussLegendre {
  static constexpr int kN = 12;
  std::array<double, kN> x{}, w{};
  GaussLegendre() {
    for (int i = 0; i < kN; ++i) {
      double z = std::cos(std::numbers::pi * (i + 0.75) / (kN + 0.5));
      double dp = 0.0;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1.0, p1 = z;
        for (int k = 2; k <= kN; ++k) {
          const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        dp = kN * (z * p1 - p0) / (z * z - 1.0);
        const double step = p1 / dp;
        z -= step;
        if (std::abs(step) < 1e-17) break;
      }
      x[static_cast<std::size_t>(i)] = z;
      w[static_cast<std::size_t>(i)] = 2.0 / ((1.0 - z * z) * dp * dp);
    }
  }
};

const GaussLegendre& Nodes() {
  static const GaussLegendre nodes;
  return nodes;
}

// The summand n_e g_e^2 on one of the three pieces: `lags` S terms (S(e), S(e-m), S(e-2m)) are
// switched on; weight T on the first two pieces, N - e on the last.
struct Piece {
  std::int64_t m;
  std::int64_t n;
  int lags;  // 1, 2 or 3

  double Weight(double e) const {
    return lags == 3 ? static_cast<double>(n) - e : static_cast<double>(n - 2 * m + 1);
  }
  double AtInteger(std::int64_t e) const {
    double g = CumulativeAt(e);
    if (lags >= 2) g -= 2.0 * CumulativeAt(e - m);
    if (lags >= 3) g += CumulativeAt(e - 2 * m);
    g /= static_cast<double>(m);
    return g * g * Weight(static_cast<double>(e));
  }
  // Real e at least kExact past the last switch-on.
  double AtReal(double e) const {
    const double md = static_cast<double>(m);
    double g = LargeCumulative(e + 1.0);
    if (lags >= 2) g -= 2.0 * LargeCumulative(e - md + 1.0);
    if (lags >= 3) g += LargeCumulative(e - 2.0 * md + 1.0);
    g /= md;
    return g * g * Weight(e);
  }
};

// sum_{e=first}^{last} of the piece's summand; `first` is where its newest S term switches on.
double SumPiece(const Piece& piece, std::int64_t first, std::int64_t last) {
  if (last < first) return 0.0;
  double total = 0.0;
  if (last - first + 1 <= kExact + 4 * kOrder) {
    for (std::int64_t e = first; e <= last; ++e) total += piece.AtInteger(e);
    return total;
  }
  const std::int64_t a = first + kExact;
  for (std::int64_t e = first; e < a; ++e) total += piece.AtInteger(e);
  // Gregory: sum_{e=a}^{b} F(e) = int_a^b F + (F(a) + F(b))/2 + sum_j c_j (nabla^j F(b) + (-1)^j
  // Delta^j F(a)).
  const std::int64_t b = last;
  std::array<double, kOrder + 1> head{}, tail{};
  for (int i = 0; i <= kOrder; ++i) {
    head[static_cast<std::size_t>(i)] = piece.AtInteger(a + i);
    tail[static_cast<std::size_t>(i)] = piece.AtInteger(b - i);
  }
  double correction = 0.5 * (head[0] + tail[0]);
  for (int j = 1; j <= kOrder; ++j) {
    // In-place differences: head[i] <- head[i+1] - head[i] (forward), tail likewise (backward).
    for (int i = 0; i + j <= kOrder; ++i) {
      head[static_cast<std::size_t>(i)] = head[static_cast<std::size_t>(i + 1)] - head[static_cast<std::size_t>(i)];
      tail[static_cast<std::size_t>(i)] = tail[static_cast<std::size_t>(i)] - tail[static_cast<std::size_t>(i + 1)];
    }
    const double sign = j % 2 == 0 ? 1.0 : -1.0;
    correction += kGregory[static_cast<std::size_t>(j - 1)] * (tail[0] + sign * head[0]);
  }
  // Integral on panels whose length doubles with the distance from the switch-on point.
  const GaussLegendre& gl = Nodes();
  double integral = 0.0;
  const double origin = static_cast<double>(first);
  double lo = static_cast<double>(a);
  const double hi = static_cast<double>(b);
  while (lo < hi) {
    const double up = std::min(hi, origin + 2.0 * (lo - origin));
    const double half = 0.5 * (up - lo), mid = 0.5 * (up + lo);
    double panel = 0.0;
    for (int i = 0; i < GaussLegendre::kN; ++i) {
      panel += gl.w[static_cast<std::size_t>(i)] * piece.AtReal(mid + half * gl.x[static_cast<std::size_t>(i)]);
    }
    integral += half * panel;
    lo = up;
  }
  return total + integral + correction;
}

}  // namespace

double KasdinCumulative(double v) {
  if (v < 0.0) return 0.0;
  if (v == std::floor(v) && v <= static_cast<double>(kExact)) {
    return SmallTable()[static_cast<std::size_t>(v)];
  }
  if (v + 1.0 >= static_cast<double>(kExact + 1)) return LargeCumulative(v + 1.0);
  return 2.0 / std::sqrt(std::numbers::pi) * std::exp(std::lgamma(v + 1.5) - std::lgamma(v + 1.0));
}

double KasdinOverlappingAvar(std::int64_t m, std::int64_t n) {
  if (m < 1 || 2 * m > n) return 0.0;
  // A few record lengths (a record, its halves) times their curves' m: a small map, one per
  // thread (fits call this per m of every evaluation from both threads: a shared lock contended).
  constexpr std::size_t kMaxEntries = 1 << 16;
  thread_local std::map<std::pair<std::int64_t, std::int64_t>, double> memo;
  return ThreadMemo(memo, kMaxEntries, {m, n}, [&] { return KasdinOverlappingAvarUncached(m, n); });
}

double KasdinOverlappingAvarUncached(std::int64_t m, std::int64_t n) {
  if (m < 1 || 2 * m > n) return 0.0;
  const double total = SumPiece({m, n, 1}, 0, m - 1) + SumPiece({m, n, 2}, m, 2 * m - 1) +
                       SumPiece({m, n, 3}, 2 * m, n - 1);
  return 0.5 * total / static_cast<double>(n - 2 * m + 1);
}

}  // namespace allanlab::sim
