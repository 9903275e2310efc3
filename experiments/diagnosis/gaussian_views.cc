#include "experiments/diagnosis/gaussian_views.h"

#include <cmath>
#include <cstdlib>
#include <limits>
#include <type_traits>
#include <variant>

#include "estimators/exact_avar_variance.h"

namespace allanlab::experiments {
namespace {

// n / sum_{|h|<n} (1 - |h|/n) rho(h)^4 for the n increments of the block sums of m samples,
// rho(h) = Cov(D_0, D_h) / Var(D_0) with Cov(D_0, D_h) proportional to the fourth difference of
// V at step m, lag h m (exact_avar_variance.h).
double KurtosisEffectiveCount(const std::vector<long double>& variogram, std::int64_t m, std::int64_t num_samples) {
  const std::int64_t n = num_samples / m - 1;
  if (n < 3) return std::numeric_limits<double>::quiet_NaN();
  auto v = [&](std::int64_t k) { return variogram[static_cast<std::size_t>(std::llabs(k))]; };
  auto cov = [&](std::int64_t k) {
    return static_cast<double>(-(6.0L * v(k) - 4.0L * v(k + m) - 4.0L * v(k - m) + v(k + 2 * m) + v(k - 2 * m)));
  };
  const double c0 = cov(0);
  if (!(c0 > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  double sum = 1.0;
  for (std::int64_t h = 1; h < n; ++h) {
    const double rho = cov(h * m) / c0;
    sum += 2.0 * (1.0 - static_cast<double>(h) / static_cast<double>(n)) * rho * rho * rho * rho;
  }
  return static_cast<double>(n) / sum;
}

}  // namespace

bool IsGaussianModel(const sim::SensorModel& model) {
  if (model.angle_quantizer || model.rate_quantizer) return false;
  for (const sim::NoiseTerm& term : model.terms) {
    const bool gaussian = std::visit(
        [](const auto& t) {
          using T = std::decay_t<decltype(t)>;
          return std::is_same_v<T, sim::QuantizationNoise> || std::is_same_v<T, sim::WhiteRateNoise> ||
                 std::is_same_v<T, sim::FlickerNoise> || std::is_same_v<T, sim::FlickerGaussMarkovSum> ||
                 std::is_same_v<T, sim::RandomWalkRate> || std::is_same_v<T, sim::RateRamp> ||
                 std::is_same_v<T, sim::GaussMarkov> || std::is_same_v<T, sim::Resonance>;
        },
        term);
    if (!gaussian) return false;
  }
  return true;
}

GaussianViewTheory ExactGaussianViews(const sim::SensorModel& model, const ViewLayout& layout) {
  if (!IsGaussianModel(model)) return {};
  const std::int64_t n = layout.num_samples;
  // Every lag either view reads is at most N (OHVAR: (T - 1) + 3m = N; the increments:
  // (blocks - 1) m + m <= N).
  const std::vector<long double> variogram = estimators::PhaseVariogram(model.GaussianAutocovariance(n + 1), n + 1);
  GaussianViewTheory t;
  for (std::int64_t m : layout.hadamard_m) {
    const estimators::AvarMoments moments = estimators::ExactOhvarMomentsFromVariogram(variogram, m, n);
    if (!(moments.mean > 0.0) || !(moments.variance > 0.0)) return {};
    t.hadamard_mean.push_back(moments.mean);
    t.hadamard_edf.push_back(moments.edf());
  }
  for (std::int64_t m : layout.kurtosis_m) t.kurtosis_effective_count.push_back(KurtosisEffectiveCount(variogram, m, n));
  return t;
}

}  // namespace allanlab::experiments
