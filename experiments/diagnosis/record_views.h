#pragma once
// The views through which `diagnose` compares a record with a model (docs/theory.md §6.1): each is a
// vector of statistics of the record, computed identically on the real record and on records
// simulated from the model, so the simulated ones form its envelope.
//   oavar:    ln OAVAR(m) on the fit's tau grid (drift-sensitive, the curve people look at)
//   hadamard: ln OHVAR(m), octave taus up to N/6 (insensitive to a rate ramp)
//   halves:   ln(OAVAR_first(m) / OAVAR_second(m)), the two halves of the record, octave m up to
//             N/16: a non-stationarity (step, warm-up drift) makes the halves differ
//   dynamic:  ln(max/min) over 8 consecutive windows of OAVAR(m), octave m up to N/64: a sliding
//             (dynamic) Allan variance reduced to its spread
//   psd:      ln of the Welch PSD (Hann, 50 % overlap, segments of 2^k <= min(N/8, 2^14)
//             samples) averaged in log-spaced bands of 6 per decade
//   kurtosis: excess kurtosis of the first differences of non-overlapping block means of m
//             samples, octave m with >= 256 blocks: ~0 for Gaussian noise of any spectrum,
//             > 0 for spikes or jumps, < 0 for a two-level (telegraph) signal
//   change_point, trend: the record's block means (16, 32, 64 blocks) against the model's
//             block-mean covariance: the largest step and the largest exponential settling, and
//             when (block_means.h); computed against each model, whose steps and drifts it places
//             in time, with its own exact null, so ComputeViews leaves them NaN
// Logs make the statistics nearly Gaussian across realisations, so one mean and one standard
// deviation per point describe the envelope.
#include <bitset>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/sample_clock.h"

namespace allanlab::experiments {

enum class View { kOavar, kHadamard, kHalves, kDynamic, kPsd, kKurtosis, kChangePoint, kTrend };
inline constexpr View kAllViews[] = {View::kOavar,    View::kHadamard,    View::kHalves,
                                     View::kDynamic,  View::kPsd,         View::kKurtosis,
                                     View::kChangePoint, View::kTrend};
inline constexpr int kNumViews = 8;
// Which views to compute (bit static_cast<int>(View)): a residual that is not read need not be
// simulated.
using ViewSet = std::bitset<kNumViews>;
inline ViewSet EveryView() { return ViewSet().set(); }
// The views whose distribution comes from a Monte Carlo envelope (envelope.h).
inline ViewSet MonteCarloViews() {
  ViewSet s = EveryView();
  s.reset(static_cast<int>(View::kOavar));
  s.reset(static_cast<int>(View::kChangePoint));
  s.reset(static_cast<int>(View::kTrend));
  return s;
}
inline ViewSet ViewSetOf(const std::vector<View>& views) {
  ViewSet s;
  for (View v : views) s.set(static_cast<int>(v));
  return s;
}
// "oavar", "hadamard", "halves", "dynamic", "psd", "kurtosis", "change_point", "trend" (stable
// JSON ids).
std::string_view ViewId(View v);
// "tau_s", "frequency_hz" or (block-mean views) "block_s".
std::string_view ViewAxisName(View v);

// The dynamic view's windows.
inline constexpr int kDynamicWindows = 8;

// Where each view is evaluated for a record of N samples at tau0 (the same for real and
// simulated records).
struct ViewLayout {
  SampleClock sample_clock;
  std::int64_t num_samples = 0;
  std::vector<std::int64_t> oavar_m;  // the fit's grid
  std::vector<std::int64_t> hadamard_m, halves_m, dynamic_m, kurtosis_m;
  std::vector<int> block_counts;                  // block-mean views: blocks of N / count samples
  // K fitted to this record: the largest K it allows (the fit's 95 % upper end or upper limit)
  // [rad/s/sqrt(s)]; 0: K held (block_means.h).
  double rate_random_walk_bound = 0.0;
  std::int64_t psd_segment = 0;                   // 0: no PSD view (record too short)
  std::vector<std::pair<int, int>> psd_bands;     // [first, last) periodogram bins per band
  std::vector<double> psd_band_hz;                // geometric centre frequency of each band
  // x (tau in s, or frequency in Hz) of every point of a view.
  std::vector<double> Axis(View v) const;
  std::size_t Size(View v) const { return Axis(v).size(); }
};

// oavar_m: the fit's averaging factors (ascending, <= N/2).
ViewLayout MakeViewLayout(SampleClock sample_clock, std::int64_t num_samples,
                          std::vector<std::int64_t> oavar_m);

// Statistics of one record per view (indexed by static_cast<int>(View)), sizes as the layout.
using ViewValues = std::vector<std::vector<double>>;

// Returns false with *why for a record whose length differs from the layout or that has a
// non-finite sample. Values a record cannot give (a constant stretch: log 0) are NaN, and so are
// the views not in `wanted` (each view's values do not depend on which others are computed).
bool ComputeViews(const ViewLayout& layout, std::span<const double> rate_rad_per_s,
                  ViewValues* values, std::string* why, const ViewSet& wanted = EveryView());

}  // namespace allanlab::experiments
