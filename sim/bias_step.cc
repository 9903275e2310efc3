#include "sim/bias_step.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <map>
#include <tuple>

#include "common/thread_memo.h"

namespace allanlab::sim {

bool BiasStep::IsValid(std::string* why) const {
  if (!std::isfinite(size_rad_per_s)) {
    if (why) *why = "bias_step size must be finite";
    return false;
  }
  return CheckNonNegative(time_s, "bias_step time", why);
}

std::int64_t BiasStep::StepIndex(double tau0_s) const {
  return static_cast<std::int64_t>(std::ceil(time_s / tau0_s - 1e-9));
}

void BiasStep::AddTo(Engine&, double tau0_s, std::span<double> rate,
                     std::int64_t first_index) const {
  const std::int64_t first = StepIndex(tau0_s) - first_index;
  for (std::int64_t k = std::max<std::int64_t>(first, 0); k < static_cast<std::int64_t>(rate.size());
       ++k) {
    rate[k] += size_rad_per_s;
  }
}

double BiasStep::ExpectedAvar(std::int64_t m, double tau0_s, const RecordShape& shape,
                              const std::vector<double>& held_response) const {
  if (!held_response.empty()) return ExpectedAvarUncached(m, tau0_s, shape, held_response);
  using Key = std::tuple<std::uint64_t, std::int64_t, std::int64_t, std::int64_t, int>;
  constexpr std::size_t kMaxEntries = 1 << 14;
  thread_local std::map<Key, double> memo;
  const Key key{std::bit_cast<std::uint64_t>(size_rad_per_s), StepIndex(tau0_s), m, shape.num_samples, static_cast<int>(shape.estimator)};
  return ThreadMemo(memo, kMaxEntries, key, [&] { return ExpectedAvarUncached(m, tau0_s, shape, held_response); });
}

double BiasStep::ExpectedAvarUncached(std::int64_t m, double tau0_s, const RecordShape& shape,
                                      const std::vector<double>& held_response) const {
  const std::int64_t s = StepIndex(tau0_s);
  std::vector<double> step_response(held_response.size() + 1, 1.0);  // cumulative sum of q
  double acc = 0.0;
  for (std::size_t j = 0; j < held_response.size(); ++j) step_response[j] = acc += held_response[j];
  if (held_response.empty()) step_response = {1.0};
  const auto width = static_cast<std::int64_t>(step_response.size());
  auto y = [&](std::int64_t k) {
    const std::int64_t d = k - s;
    if (d < 0) return 0.0;
    return size_rad_per_s * (d < width ? step_response[d] : step_response.back());
  };
  return DeterministicAvar(y, s - 2 * m, s + width, m, shape);
}

}  // namespace allanlab::sim
