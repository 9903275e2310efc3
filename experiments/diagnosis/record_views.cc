#include "experiments/diagnosis/record_views.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "estimators/allan_family.h"
#include "experiments/diagnosis/block_kurtosis.h"
#include "experiments/diagnosis/block_means.h"
#include "experiments/diagnosis/welch_psd.h"

namespace allanlab::experiments {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::vector<std::int64_t> Octaves(std::int64_t max_m) {
  std::vector<std::int64_t> m;
  for (std::int64_t v = 1; v <= max_m; v *= 2) m.push_back(v);
  return m;
}

// The statistic at exactly the averaging factors `ms` (NaN where the estimator gives none).
std::vector<double> StatisticAt(estimators::Statistic statistic, double tau0,
                              std::span<const std::int64_t> ms, std::span<const double> rate) {
  std::vector<double> out(ms.size(), kNaN);
  if (ms.empty()) return out;
  estimators::AvarOptions options;
  options.statistic = statistic;
  options.sample_clock = SampleClock::FromPeriodS(tau0);
  options.confidence_method = estimators::ConfidenceMethod::kNone;
  options.taus.kind = estimators::TauGridKind::kExplicit;
  for (std::int64_t m : ms) options.taus.explicit_taus_s.push_back(static_cast<double>(m) * tau0);
  estimators::AvarSummary summary;
  if (!estimators::ComputeStatisticValues(options, rate, &summary)) return out;
  for (const auto& point : summary.points) {
    const auto it = std::find(ms.begin(), ms.end(), point.m);
    if (it != ms.end()) out[it - ms.begin()] = point.value;
  }
  return out;
}

double SafeLog(double v) { return v > 0.0 ? std::log(v) : kNaN; }

std::vector<double> Logs(std::vector<double> v) {
  for (double& x : v) x = SafeLog(x);
  return v;
}

// ln(OAVAR of the first half / OAVAR of the second) at layout.halves_m.
void HalvesView(const ViewLayout& layout, std::span<const double> rate, std::vector<double>* halves) {
  using estimators::Statistic;
  const double tau0 = layout.sample_clock.period_s();
  const std::size_t half = rate.size() / 2;
  const auto first = StatisticAt(Statistic::kAllanOverlapping, tau0, layout.halves_m, rate.first(half));
  const auto second =
      StatisticAt(Statistic::kAllanOverlapping, tau0, layout.halves_m, rate.subspan(half, half));
  for (std::size_t i = 0; i < first.size(); ++i) halves->push_back(SafeLog(first[i]) - SafeLog(second[i]));
}

// ln(max / min) of OAVAR(m) over 8 consecutive windows, at layout.dynamic_m.
void DynamicView(const ViewLayout& layout, std::span<const double> rate, std::vector<double>* dynamic) {
  using estimators::Statistic;
  const double tau0 = layout.sample_clock.period_s();
  const std::size_t window = rate.size() / kDynamicWindows;
  dynamic->assign(layout.dynamic_m.size(), kNaN);
  if (layout.dynamic_m.empty()) return;
  std::vector<double> lo(layout.dynamic_m.size(), std::numeric_limits<double>::infinity());
  std::vector<double> hi(layout.dynamic_m.size(), -std::numeric_limits<double>::infinity());
  for (int w = 0; w < kDynamicWindows; ++w) {
    const auto a = StatisticAt(Statistic::kAllanOverlapping, tau0, layout.dynamic_m, rate.subspan(w * window, window));
    for (std::size_t i = 0; i < a.size(); ++i) {
      lo[i] = std::min(lo[i], SafeLog(a[i]));
      hi[i] = std::max(hi[i], SafeLog(a[i]));
    }
  }
  for (std::size_t i = 0; i < dynamic->size(); ++i) {
    if (std::isfinite(lo[i]) && std::isfinite(hi[i])) (*dynamic)[i] = hi[i] - lo[i];
  }
}

// ln of the Welch PSD (Hann, 50 % overlap) averaged in the layout's bands.
void PsdView(const ViewLayout& layout, std::span<const double> rate, std::vector<double>* psd) {
  if (layout.psd_segment <= 0) return;
  const std::vector<double> density =
      WelchPsd(rate, static_cast<std::size_t>(layout.psd_segment), layout.sample_clock.period_s());
  for (const auto& [b0, b1] : layout.psd_bands) {
    double s = 0.0;
    for (int b = b0; b < b1; ++b) s += density[static_cast<std::size_t>(b)];
    psd->push_back(SafeLog(s / (b1 - b0)));
  }
}

}  // namespace

std::string_view ViewId(View v) {
  switch (v) {
    case View::kOavar: return "oavar";
    case View::kHadamard: return "hadamard";
    case View::kHalves: return "halves";
    case View::kDynamic: return "dynamic";
    case View::kPsd: return "psd";
    case View::kKurtosis: return "kurtosis";
    case View::kChangePoint: return "change_point";
    case View::kTrend: return "trend";
  }
  return "?";
}

std::string_view ViewAxisName(View v) {
  if (v == View::kChangePoint || v == View::kTrend) return "block_s";
  return v == View::kPsd ? "frequency_hz" : "tau_s";
}

std::vector<double> ViewLayout::Axis(View v) const {
  auto taus = [&](const std::vector<std::int64_t>& ms) {
    std::vector<double> x;
    for (std::int64_t m : ms) x.push_back(static_cast<double>(m) * sample_clock.period_s());
    return x;
  };
  switch (v) {
    case View::kOavar: return taus(oavar_m);
    case View::kHadamard: return taus(hadamard_m);
    case View::kHalves: return taus(halves_m);
    case View::kDynamic: return taus(dynamic_m);
    case View::kPsd: return psd_band_hz;
    case View::kKurtosis: return taus(kurtosis_m);
    case View::kChangePoint:
    case View::kTrend: {
      std::vector<double> x;
      for (int b : block_counts) x.push_back(static_cast<double>(num_samples / b) * sample_clock.period_s());
      return x;
    }
  }
  return {};
}

ViewLayout MakeViewLayout(SampleClock sample_clock, std::int64_t num_samples,
                          std::vector<std::int64_t> oavar_m) {
  ViewLayout l;
  l.sample_clock = sample_clock;
  l.num_samples = num_samples;
  l.oavar_m = std::move(oavar_m);
  const std::int64_t n = num_samples;
  l.hadamard_m = Octaves(n / 6);
  l.halves_m = Octaves(n / 16);
  l.dynamic_m = Octaves(n / 64);
  l.kurtosis_m = Octaves(n / 256);
  l.block_counts = BlockMeanCounts(n);
  std::int64_t seg = 1;
  while (seg * 2 <= std::min<std::int64_t>(n / 8, std::int64_t{1} << 14)) seg *= 2;
  if (seg >= 64) {
    l.psd_segment = seg;
    const double df = 1.0 / (static_cast<double>(seg) * sample_clock.period_s());
    const int last_bin = static_cast<int>(seg / 2) - 1;  // below Nyquist
    // Bands of 6 per decade in frequency from bin 1; a band holds at least one bin.
    const double ratio = std::pow(10.0, 1.0 / 6.0);
    int first = 1;
    double edge = 1.0;
    while (first <= last_bin) {
      edge *= ratio;
      int end = std::max(first + 1, static_cast<int>(std::ceil(edge)));
      end = std::min(end, last_bin + 1);
      l.psd_bands.emplace_back(first, end);
      l.psd_band_hz.push_back(std::sqrt(static_cast<double>(first) * (end - 1)) * df);
      first = end;
    }
  }
  return l;
}

bool ComputeViews(const ViewLayout& layout, std::span<const double> rate, ViewValues* values,
                  std::string* why, const ViewSet& wanted) {
  if (static_cast<std::int64_t>(rate.size()) != layout.num_samples) {
    *why = "record length differs from the view layout";
    return false;
  }
  for (std::size_t k = 0; k < rate.size(); ++k) {
    if (!std::isfinite(rate[k])) {
      *why = "sample " + std::to_string(k) + " is not finite";
      return false;
    }
  }
  const double tau0 = layout.sample_clock.period_s();
  ViewValues& v = *values;
  v.assign(kNumViews, {});
  auto want = [&](View view) {
    if (wanted.test(static_cast<int>(view))) return true;
    v[static_cast<int>(view)].assign(layout.Size(view), kNaN);
    return false;
  };
  using estimators::Statistic;
  if (want(View::kOavar)) {
    v[static_cast<int>(View::kOavar)] = Logs(StatisticAt(Statistic::kAllanOverlapping, tau0, layout.oavar_m, rate));
  }
  if (want(View::kHadamard)) {
    v[static_cast<int>(View::kHadamard)] =
        Logs(StatisticAt(Statistic::kHadamardOverlapping, tau0, layout.hadamard_m, rate));
  }
  if (want(View::kHalves)) HalvesView(layout, rate, &v[static_cast<int>(View::kHalves)]);
  if (want(View::kDynamic)) DynamicView(layout, rate, &v[static_cast<int>(View::kDynamic)]);
  if (want(View::kPsd)) PsdView(layout, rate, &v[static_cast<int>(View::kPsd)]);
  if (want(View::kKurtosis)) v[static_cast<int>(View::kKurtosis)] = BlockIncrementKurtosis(rate, layout.kurtosis_m);
  v[static_cast<int>(View::kChangePoint)].assign(layout.block_counts.size(), kNaN);
  v[static_cast<int>(View::kTrend)].assign(layout.block_counts.size(), kNaN);
  return true;
}

}  // namespace allanlab::experiments
