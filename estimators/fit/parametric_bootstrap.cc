#include "estimators/fit/parametric_bootstrap.h"

#include <cmath>
#include <sstream>

#include "estimators/allan_variance.h"

namespace allanlab::estimators {

bool BootstrapOptions::IsValid(std::string* why) const {
  if (trials < 2) {
    if (why) {
      std::ostringstream os;
      os << "bootstrap: at least 2 replicates are needed for a standard deviation, got " << trials;
      *why = os.str();
    }
    return false;
  }
  return true;
}

BootstrapSpread ParametricBootstrap(const sim::SensorModel& model, const AvarCurve& curve,
                                    const BootstrapOptions& options, std::size_t parameters,
                                    const BootstrapRefit& refit) {
  const int trials = options.trials;
  std::vector<std::vector<double>> values(static_cast<std::size_t>(trials));
  std::vector<char> ok(static_cast<std::size_t>(trials), 0);
  std::vector<std::string> why(static_cast<std::size_t>(trials));
  // One replicate per iteration, each into its own slot: no shared writes, no exception may
  // leave the region (a failed refit is a status, not a throw).
#pragma omp parallel for schedule(dynamic, 1)
  for (int r = 0; r < trials; ++r) {
    const auto slot = static_cast<std::size_t>(r);
    AvarCurve replicate = curve;
    const std::vector<double> record =
        model.Generate(options.seed, static_cast<std::uint64_t>(r), curve.num_samples);
    replicate.avar = AllanVariance(record, curve.m, curve.estimator);
    values[slot].assign(parameters, 0.0);
    ok[slot] = refit(replicate, &values[slot], &why[slot]) ? 1 : 0;
  }
  BootstrapSpread out;
  out.trials = trials;
  out.mean.assign(parameters, 0.0);
  out.sigma.assign(parameters, 0.0);
  // Two passes in replicate order (mean, then squared deviations): deterministic and free of the
  // cancellation of a one-pass variance.
  for (int r = 0; r < trials; ++r) {
    const auto slot = static_cast<std::size_t>(r);
    if (!ok[slot]) {
      if (out.first_failure.empty()) {
        std::ostringstream os;
        os << "replicate " << r << ": " << why[slot];
        out.first_failure = os.str();
      }
      continue;
    }
    ++out.used;
    for (std::size_t p = 0; p < parameters; ++p) out.mean[p] += values[slot][p];
  }
  if (out.used == 0) return out;
  for (double& m : out.mean) m /= out.used;
  if (out.used < 2) return out;
  for (int r = 0; r < trials; ++r) {
    const auto slot = static_cast<std::size_t>(r);
    if (!ok[slot]) continue;
    for (std::size_t p = 0; p < parameters; ++p) {
      const double d = values[slot][p] - out.mean[p];
      out.sigma[p] += d * d;
    }
  }
  for (double& s : out.sigma) s = std::sqrt(s / (out.used - 1));
  return out;
}

}  // namespace allanlab::estimators
