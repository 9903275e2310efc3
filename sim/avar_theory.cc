#include "sim/avar_theory.h"

#include <algorithm>
#include <vector>

namespace allanlab::sim {

AllanStarts AllanDifferenceStarts(std::int64_t m, const RecordShape& shape) {
  const std::int64_t n = shape.num_samples;
  if (m < 1 || 2 * m > n) return {0, 1};
  if (shape.estimator == AvarEstimatorKind::kOverlapping) return {n - 2 * m + 1, 1};
  return {n / m - 1, m};
}

double AllanLagWeight(std::int64_t m, std::int64_t j) {
  if (j < 0) j = -j;
  if (j <= m) return static_cast<double>(2 * m - 3 * j);
  if (j < 2 * m) return -static_cast<double>(2 * m - j);
  return 0.0;
}

double AvarFromAutocovariance(std::int64_t m, std::span<const double> autocovariance) {
  // Long double: for random walk the lag terms grow like m^3 and cancel to O(m).
  long double sum = static_cast<long double>(2 * m) * autocovariance[0];
  for (std::int64_t j = 1; j < 2 * m; ++j) {
    sum += 2.0L * AllanLagWeight(m, j) * static_cast<long double>(autocovariance[j]);
  }
  return static_cast<double>(sum / (2.0L * m * m));
}

double FiniteRecordAvar(std::span<const double> cumulative_p, double innovation_var,
                        std::int64_t m, std::int64_t offset, const RecordShape& shape) {
  return ScaledFiniteRecordAvar(FiniteRecordAvarSum(cumulative_p, m, offset, shape), innovation_var);
}

double ScaledFiniteRecordAvar(const FiniteRecordSum& sum, double innovation_var) {
  if (sum.count == 0) return 0.0;
  return static_cast<double>(0.5L * innovation_var * sum.total / sum.count);
}

FiniteRecordSum FiniteRecordAvarSum(std::span<const double> cumulative_p, std::int64_t m, std::int64_t offset,
                                    const RecordShape& shape) {
  const AllanStarts starts = AllanDifferenceStarts(m, shape);
  if (starts.count == 0) return {};
  const std::int64_t last_start = (starts.count - 1) * starts.stride;
  const std::int64_t first_end = offset + 2 * m - 1;
  const std::int64_t e_max = first_end + last_start;
  // With G(L) = sum_{e<=L} g_e^2, g_e = (S(e) - 2 S(e-m) + S(e-2m)) / m, the estimator sums
  // G at its end points L = first_end + j stride, j < count; that is sum_e g_e^2 n_e with n_e the
  // number of end points >= e. One vectorisable weighted sum (double lanes, compensated per
  // block) instead of a long double running sum: ~1e-15 relative, and 60 taus of a 1e6-sample
  // record no longer dominate a fit.
  const double* s = cumulative_p.data();
  const double inv_m = 1.0 / static_cast<double>(m);
  auto g_at = [&](std::int64_t e) {
    const double a = s[e];
    const double b = e >= m ? s[e - m] : 0.0;
    const double c = e >= 2 * m ? s[e - 2 * m] : 0.0;
    return (a - 2.0 * b + c) * inv_m;
  };
  auto ends_from = [&](std::int64_t e) {  // n_e
    if (e <= first_end) return static_cast<double>(starts.count);
    return static_cast<double>(starts.count - (e - first_end + starts.stride - 1) / starts.stride);
  };
  long double total = 0.0L;
  std::int64_t e = 0;
  // Head (e < 2m: some S terms are zero) one by one.
  for (; e <= e_max && e < 2 * m; ++e) {
    const double g = g_at(e);
    total += static_cast<long double>(g * g) * ends_from(e);
  }
  constexpr std::int64_t kBlock = 4096;
  while (e <= e_max) {
    const std::int64_t end = std::min(e_max + 1, e + kBlock);
    double lanes[4] = {0.0, 0.0, 0.0, 0.0};
    if (starts.stride == 1 && e > first_end) {
      // n_e = count - (e - first_end) = base - e.
      const auto base = static_cast<double>(starts.count + first_end);
      for (; e + 4 <= end; e += 4) {
        for (int l = 0; l < 4; ++l) {
          const std::int64_t x = e + l;
          const double g = (s[x] - 2.0 * s[x - m] + s[x - 2 * m]) * inv_m;
          lanes[l] += g * g * (base - static_cast<double>(x));
        }
      }
    }
    for (; e < end; ++e) {
      const double g = g_at(e);
      lanes[0] += g * g * ends_from(e);
    }
    total += static_cast<long double>((lanes[0] + lanes[1]) + (lanes[2] + lanes[3]));
  }
  return {total, starts.count};
}

bool IsValidAveragingFactor(std::int64_t m, const RecordShape& shape, std::string* why) {
  if (m < 1) {
    if (why) *why = "averaging factor m must be >= 1, got " + std::to_string(m);
    return false;
  }
  if (2 * m > shape.num_samples) {
    if (why) {
      *why = "averaging factor m = " + std::to_string(m) + " needs at least 2m samples, record has " +
             std::to_string(shape.num_samples);
    }
    return false;
  }
  return true;
}

}  // namespace allanlab::sim
