#include "experiments/diagnosis/envelope.h"

#include <cmath>
#include <limits>

#include "estimators/exact_edf.h"

namespace allanlab::experiments {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Only the law of the simulated records matters to an envelope: the band-limited white noise is
// drawn per output period where that is exact (sim/section_period.h), and the flicker record
// is shared when asked (docs/theory.md §6.1).
sim::GenerateOptions EnvelopeGeneration(const SharedFlicker* shared_flicker) {
  sim::GenerateOptions options{.white_per_output_period = true};
  if (shared_flicker != nullptr) {
    options.flicker_cache = shared_flicker->cache;
    options.flicker_seed = shared_flicker->seed;
  }
  return options;
}

}  // namespace

OavarTheory ExactOavar(const sim::SensorModel& model, std::span<const std::int64_t> ms,
                       std::int64_t num_samples) {
  const sim::RecordShape shape{num_samples, sim::AvarEstimatorKind::kOverlapping};
  OavarTheory t;
  t.mean = model.ExpectedAvar(ms, shape);
  const auto moments = estimators::ModelAvarMoments(model, ms, shape);
  for (std::size_t i = 0; i < ms.size(); ++i) {
    // The deterministic share of the mean adds no variance of its own; keeping the Gaussian
    // variance with the total mean makes the interval no narrower than the Gaussian part's.
    const double gaussian_edf = moments[i].edf();
    const double total_edf =
        moments[i].variance > 0.0 ? 2.0 * t.mean[i] * t.mean[i] / moments[i].variance : 0.0;
    t.edf.push_back(std::min(gaussian_edf > 0.0 ? gaussian_edf : total_edf, total_edf));
  }
  return t;
}

bool SimulateEnvelope(const sim::SensorModel& model, const ViewLayout& layout, int trials,
                      std::uint64_t seed, ViewEnvelope* envelope, std::string* why, const ViewSet& wanted,
                      const SharedFlicker* shared_flicker) {
  if (!model.IsValid(why)) return false;
  const sim::GenerateOptions generation = EnvelopeGeneration(shared_flicker);
  std::vector<ViewValues> per_trial(trials);
  std::vector<char> ok(trials, 0);
#pragma omp parallel for schedule(dynamic, 1)
  for (int t = 0; t < trials; ++t) {
    const std::vector<double> record =
        model.Generate(seed, static_cast<std::uint64_t>(t), layout.num_samples, generation);
    std::string ignored;
    ok[t] = ComputeViews(layout, record, &per_trial[t], &ignored, wanted) ? 1 : 0;
  }
  ViewEnvelope& e = *envelope;
  e = ViewEnvelope{};
  e.mean.assign(kNumViews, {});
  e.sd.assign(kNumViews, {});
  for (int v = 0; v < kNumViews; ++v) {
    const std::size_t size = layout.Size(static_cast<View>(v));
    e.mean[v].assign(size, 0.0);
    e.sd[v].assign(size, 0.0);
    for (std::size_t i = 0; i < size; ++i) {
      double sum = 0.0, sum2 = 0.0;
      int n = 0;
      for (int t = 0; t < trials; ++t) {
        if (!ok[t]) continue;
        const double x = per_trial[t][v][i];
        if (!std::isfinite(x)) continue;
        sum += x;
        ++n;
      }
      const double mean = n > 0 ? sum / n : std::nan("");
      for (int t = 0; t < trials; ++t) {
        if (!ok[t] || !std::isfinite(per_trial[t][v][i])) continue;
        sum2 += (per_trial[t][v][i] - mean) * (per_trial[t][v][i] - mean);
      }
      e.mean[v][i] = mean;
      e.sd[v][i] = n > 1 ? std::sqrt(sum2 / (n - 1)) : std::nan("");
    }
  }
  for (int t = 0; t < trials; ++t) e.trials += ok[t];
  if (e.trials == 0) {
    *why = "no simulated record of the model gave view statistics";
    return false;
  }
  return true;
}

std::vector<ViewResiduals> Residuals(const ViewLayout& layout, const ViewValues& observed,
                                     const OavarTheory& theory, const ViewEnvelope* envelope,
                                     const ViewSet& wanted, const GaussianViewTheory* gaussian) {
  std::vector<ViewResiduals> out;
  for (View view : kAllViews) {
    const int v = static_cast<int>(view);
    if (view == View::kChangePoint || view == View::kTrend) continue;  // against each model (block_means.h)
    if (!wanted.test(v)) continue;
    ViewResiduals r;
    r.view = view;
    r.x = layout.Axis(view);
    const bool log_scale = view == View::kOavar || view == View::kHadamard || view == View::kPsd;
    const bool from_theory = gaussian != nullptr && view != View::kOavar;
    if (from_theory && r.x.empty()) continue;
    if (view == View::kOavar) {
      for (std::size_t i = 0; i < r.x.size(); ++i) {
        const double obs = std::exp(observed[v][i]);
        r.observed.push_back(obs);
        r.expected.push_back(theory.mean[i]);
        r.z.push_back(ZFromChiSquare(obs, theory.mean[i], theory.edf[i]));
      }
    } else if (from_theory) {
      for (std::size_t i = 0; i < r.x.size(); ++i) {
        double expected = kNaN;
        r.z.push_back(GaussianViewZ(view, *gaussian, observed[v][i], i, &expected));
        r.observed.push_back(log_scale ? std::exp(observed[v][i]) : observed[v][i]);
        r.expected.push_back(expected);
      }
    } else {
      if (envelope == nullptr || envelope->trials < 3 || r.x.empty()) continue;
      for (std::size_t i = 0; i < r.x.size(); ++i) {
        const double obs = observed[v][i];
        const double mean = envelope->mean[v][i];
        r.observed.push_back(log_scale ? std::exp(obs) : obs);
        r.expected.push_back(log_scale ? std::exp(mean) : mean);
        const double sd = envelope->sd[v][i];
        const int trials = envelope->trials;
        r.z.push_back(view == View::kHalves     ? ZFromLogRatioEnvelope(obs, mean, sd, trials)
                      : view == View::kKurtosis ? ZFromKurtosisEnvelope(obs, mean, sd, trials)
                      : log_scale               ? ZFromLogVarianceEnvelope(obs, mean, sd, trials)
                                                : ZFromEnvelope(obs, mean, sd, trials));
      }
    }
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace allanlab::experiments
