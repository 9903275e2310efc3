#include "estimators/fit/slope_method.h"

#include <cmath>
#include <numbers>
#include <vector>

#include "sim/units.h"

namespace allanlab::estimators {
namespace {

struct LineSpec {
  Coefficient coefficient;
  double slope;      // of log ADEV vs log tau
  double read_at_s;  // the tau where the line's ADEV equals the coefficient
};

constexpr LineSpec kLines[] = {
    {Coefficient::kQ, -1.0, std::numbers::sqrt3},
    {Coefficient::kN, -0.5, 1.0},
    {Coefficient::kK, 0.5, 3.0},
    {Coefficient::kR, 1.0, std::numbers::sqrt2},
};

// Local slope of log ADEV at each point (centred differences, one-sided at the ends).
std::vector<double> LocalSlopes(const std::vector<double>& log_tau, const std::vector<double>& log_adev) {
  const std::size_t n = log_tau.size();
  std::vector<double> slope(n, 0.0);
  if (n < 2) return slope;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t lo = i == 0 ? 0 : i - 1;
    const std::size_t hi = i + 1 == n ? n - 1 : i + 1;
    slope[i] = (log_adev[hi] - log_adev[lo]) / (log_tau[hi] - log_tau[lo]);
  }
  return slope;
}

}  // namespace

SlopeMethodResult ReadSlopes(const AvarCurve& curve, const SlopeMethodOptions& options) {
  SlopeMethodResult result;
  const std::size_t n = curve.size();
  std::vector<double> log_tau(n), log_adev(n);
  for (std::size_t i = 0; i < n; ++i) {
    log_tau[i] = std::log(curve.tau_s[i]);
    log_adev[i] = 0.5 * std::log(curve.avar[i]);
  }
  const std::vector<double> slope = LocalSlopes(log_tau, log_adev);

  // The longest run of consecutive taus in [from, to) whose local slope matches `line`'s.
  auto longest_run = [&](const LineSpec& line, std::size_t from, std::size_t to) {
    std::size_t best_start = 0, best_len = 0;
    for (std::size_t i = from; i < to;) {
      if (std::abs(slope[i] - line.slope) > options.slope_tolerance) {
        ++i;
        continue;
      }
      std::size_t j = i;
      while (j < to && std::abs(slope[j] - line.slope) <= options.slope_tolerance) ++j;
      if (j - i > best_len) best_start = i, best_len = j - i;
      i = j;
    }
    return std::pair{best_start, best_len};
  };
  // The white-noise line first: the quantization line is looked for only before it and the
  // rising lines (K, R) only after it, where IEEE 952 puts them. A band-limited curve rises from
  // its first taus to the filter's peak; read as a +1/2 line that rise gave K at 3 s 10^5 times
  // too large.
  constexpr LineSpec kWhite = kLines[1];
  static_assert(kWhite.coefficient == Coefficient::kN);
  const auto [n_start, n_len] = longest_run(kWhite, 0, n);
  for (const LineSpec& line : kLines) {
    SlopeReading& r = result.readings[static_cast<int>(line.coefficient)];
    std::size_t from = 0, to = n;
    if (n_len > 0 && line.slope < -0.5) to = n_start;
    if (n_len > 0 && line.slope > 0.0) from = n_start + n_len;
    const auto [best_start, best_len] = longest_run(line, from, to);
    if (best_len == 0) {
      r.note = "no region of slope " + std::to_string(line.slope) + " on the curve" +
               (from > 0 ? " beyond the white-noise region" : to < n ? " before the white-noise region" : "");
      continue;
    }
    // log C = mean(log sigma - slope log tau) over the region; sigma(tau) = C tau^slope.
    double log_c = 0.0;
    for (std::size_t i = best_start; i < best_start + best_len; ++i) {
      log_c += log_adev[i] - line.slope * log_tau[i];
    }
    log_c /= static_cast<double>(best_len);
    r.found = true;
    r.value_si = std::exp(log_c) * std::pow(line.read_at_s, line.slope);
    r.tau_lo_s = curve.tau_s[best_start];
    r.tau_hi_s = curve.tau_s[best_start + best_len - 1];
    r.points = static_cast<int>(best_len);
    if (line.read_at_s < r.tau_lo_s || line.read_at_s > r.tau_hi_s) {
      r.note = "line extrapolated to tau = " + std::to_string(line.read_at_s) + " s";
    }
  }

  SlopeReading& b = result.readings[static_cast<int>(Coefficient::kB)];
  std::size_t imin = 0;
  for (std::size_t i = 1; i < n; ++i) {
    if (curve.avar[i] < curve.avar[imin]) imin = i;
  }
  b.found = true;
  b.value_si = std::sqrt(curve.avar[imin]) / units::kFlickerFloorFactor;
  b.tau_lo_s = b.tau_hi_s = curve.tau_s[imin];
  b.points = 1;
  if (imin + 1 == n) b.note = "minimum at the longest tau: the floor may not be reached";
  return result;
}

}  // namespace allanlab::estimators
