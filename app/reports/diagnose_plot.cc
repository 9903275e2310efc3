#include "app/reports/diagnose_plot.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "common/number_text.h"
#include "experiments/diagnosis/envelope.h"

namespace allanlab::app {
namespace {

using namespace allanlab::experiments;

constexpr const char* kBaselineColor = "#1f77b4";
constexpr const char* kModelColor = "#2ca02c";
constexpr const char* kGapColor = "#d62728";
constexpr const char* kKey = "below left horizontal";  // under the axes: never over a curve
constexpr double kStrip = 0.035;  // gap marks: a strip along the x axis, under the data

std::string Short(double v) { return SignificantDigits(v, 4); }

const ViewResiduals* Find(const std::vector<ViewResiduals>& views, View v) {
  for (const ViewResiduals& r : views) {
    if (r.view == v) return &r;
  }
  return nullptr;
}

bool TauView(View v) { return v != View::kChangePoint && v != View::kTrend; }

// The tau range of a region (the PSD's frequencies as tau = 1 / (2 f)).
std::pair<double, double> TauRange(const GapRegion& r) {
  if (r.view == View::kPsd) return {0.5 / r.x_max, 0.5 / r.x_min};
  return {r.x_min, r.x_max};
}

// A light strip along the x axis over each region of `view` on its own axis (every tau view's
// on the tau axis when `view` is empty): where the record departs, marked without covering a point.
void MarkGaps(const DiagnosisSummary& s, std::optional<View> view, const std::string& title, AllanPlot* plot) {
  for (const GapRegion& r : s.regions) {
    if (view ? r.view != *view : !TauView(r.view)) continue;
    const auto [lo, hi] = view ? std::pair(r.x_min, r.x_max) : TauRange(r);
    PlotSpan span{lo, hi, kGapColor, 0.45, title};
    span.height = kStrip;
    plot->spans.push_back(span);
  }
}

std::string ModelName(const DiagnosisSummary& s) {
  if (s.verdict_candidate < 0) return "";
  return (s.verdict == "unexplained" ? "best tried: with " : "with ") + s.candidates[s.verdict_candidate].id();
}

// The record's ADEV, each model's mean and 95 % band (the exact chi-square distribution of the
// OAVAR view), and the record's points beyond the threshold against the baseline in red on top.
AllanPlot AllanPanel(const DiagnosisSummary& s, const std::string& title, const DiagnoseUnits& units) {
  AllanPlot plot;
  plot.title = title;
  plot.key = kKey;
  plot.y_label = "Allan deviation [" + ReportRateUnit(units) + "]";
  const double unit = ReportRatePerSi(units);
  auto adev = [&](const std::vector<double>& avar) {
    std::vector<double> y;
    for (double v : avar) y.push_back(std::sqrt(v) * unit);
    return y;
  };
  // The diagnosis keeps each model's exact OAVAR; computed here only for a summary without it.
  auto band = [&](const sim::SensorModel& model, const OavarTheory& kept, const std::string& name,
                  const std::string& color, PlotSeries* line) {
    const OavarTheory t = kept.mean.size() == s.curve.size() ? kept : ExactOavar(model, s.curve.m, s.num_samples);
    PlotSeries b{name + ": 95 % band", PlotStyle::kBand, s.curve.tau_s, adev(t.mean)};
    if (name == "baseline") b.style = PlotStyle::kBandOutline;  // the verdict's filled band shows under it
    for (std::size_t i = 0; i < t.mean.size(); ++i) {
      const bool ok = t.mean[i] > 0.0 && t.edf[i] > 0.0;
      const Band r = ok ? ChiSquareBand(t.mean[i], t.edf[i], 0.95) : Band{};
      b.y_low.push_back(std::sqrt(r.low) * unit);
      b.y_high.push_back(std::sqrt(r.high) * unit);
    }
    b.color = color;
    *line = PlotSeries{name, PlotStyle::kDashedLine, s.curve.tau_s, adev(t.mean)};
    line->color = color;
    return b;
  };
  PlotSeries baseline_line, model_line;
  plot.series.push_back(band(s.baseline_model, s.baseline_theory, "baseline", kBaselineColor, &baseline_line));
  if (s.verdict_candidate >= 0) {
    const CandidateResult& verdict = s.candidates[s.verdict_candidate];
    plot.series.push_back(band(verdict.model, verdict.theory, ModelName(s), kModelColor, &model_line));
    model_line.style = PlotStyle::kLine;
  }
  PlotSeries record{"record", PlotStyle::kPoints, s.curve.tau_s, adev(s.curve.avar)};
  record.color = "#000000";
  plot.guide_series = static_cast<int>(plot.series.size());
  plot.series.push_back(record);
  plot.series.push_back(baseline_line);
  if (s.verdict_candidate >= 0) plot.series.push_back(model_line);
  if (const ViewResiduals* oavar = Find(s.before.views, View::kOavar)) {
    PlotSeries gap{"record beyond |z| = " + Short(s.threshold) + " of the baseline", PlotStyle::kPoints, {}, {}};
    gap.color = kGapColor;
    for (std::size_t i = 0; i < oavar->z.size() && i < s.curve.size(); ++i) {
      if (std::isfinite(oavar->z[i]) && std::abs(oavar->z[i]) > s.threshold) {
        gap.x.push_back(s.curve.tau_s[i]);
        gap.y.push_back(std::sqrt(s.curve.avar[i]) * unit);
      }
    }
    if (!gap.x.empty()) plot.series.push_back(gap);
  }
  MarkGaps(s, std::nullopt, "tau where a view departs from the baseline", &plot);
  return plot;
}

std::string ViewTitle(View v) {
  switch (v) {
    case View::kOavar: return "Allan variance";
    case View::kHadamard: return "Hadamard variance";
    case View::kHalves: return "first half against second half";
    case View::kDynamic: return "Allan variance along the record";
    case View::kPsd: return "power spectral density";
    case View::kKurtosis: return "kurtosis of block-mean increments";
    case View::kChangePoint:
    case View::kTrend: return "block means";
  }
  return "?";
}

std::string AxisLabel(View v) {
  if (v == View::kPsd) return "frequency [Hz]";
  return "tau [s]";
}

// One view: z of the record against the baseline and against the verdict model, with 0 and the
// gap level +-threshold.
AllanPlot ViewPanel(const DiagnosisSummary& s, View v) {
  AllanPlot plot;
  plot.title = std::string(ViewId(v)) + ": " + ViewTitle(v);
  plot.x_label = AxisLabel(v);
  plot.y_label = "standardised residual z";
  plot.log_y = false;
  plot.key = kKey;
  plot.guide_series = -1;
  plot.slope_guides.clear();
  plot.y_lines = {-s.threshold, 0.0, s.threshold};
  plot.height_px = 450;
  MarkGaps(s, v, "gap: |z| > " + Short(s.threshold), &plot);
  if (const ViewResiduals* r = Find(s.before.views, v)) {
    PlotSeries b{"record vs baseline (gap: |z| > " + Short(s.threshold) + ", dashed)", PlotStyle::kPoints, r->x, r->z};
    b.color = kBaselineColor;
    plot.series.push_back(b);
  }
  if (s.verdict_candidate >= 0) {
    if (const ViewResiduals* r = Find(s.candidates[s.verdict_candidate].after.views, v)) {
      PlotSeries m{"record vs " + ModelName(s).substr(ModelName(s).rfind("with ") + 5) + " model", PlotStyle::kLine, r->x, r->z};
      m.color = kModelColor;
      plot.series.push_back(m);
    }
  }
  return plot;
}

// The block-mean views in the time domain: the record's block means over the record, the
// baseline's level and the verdict model's (its step or warm-up drift placed in time), each level
// set to the record's mean (the bias, which no view tests) with its pointwise 95 % band (a block
// mean's spread about the mean of all blocks under that model), and the located step or the
// settling marked along the time axis.
AllanPlot BlockMeansPanel(const DiagnosisSummary& s, const DiagnoseUnits& units) {
  const BlockMeanSeries& b = s.block_means;
  AllanPlot plot;
  plot.x_label = "time in the record [s]";
  plot.y_label = "block mean of the " + QuantityWord(units) + " [" + ReportRateUnit(units) + "]";
  plot.log_x = plot.log_y = false;
  plot.key = kKey;
  plot.guide_series = -1;
  plot.slope_guides.clear();
  plot.height_px = 450;
  const double unit = ReportRatePerSi(units);
  auto mean = [](const std::vector<double>& v) {
    double sum = 0.0;
    for (double x : v) sum += x;
    return v.empty() ? 0.0 : sum / static_cast<double>(v.size());
  };
  const double level = mean(b.record);
  auto leveled = [&](const std::vector<double>& path) {
    std::vector<double> y;
    const double offset = level - mean(path);
    for (double p : path) y.push_back((p + offset) * unit);
    return y;
  };
  // Each model's pointwise 95 % band of a block mean about the record's mean level.
  auto band = [&](const std::vector<double>& centre, const std::vector<double>& sd, const std::string& name,
                  PlotStyle style, const char* color) {
    PlotSeries out{name + ": 95 % band", style, b.time_s, centre};
    for (std::size_t i = 0; i < centre.size() && i < sd.size(); ++i) {
      out.y_low.push_back(centre[i] - 1.96 * sd[i] * unit);
      out.y_high.push_back(centre[i] + 1.96 * sd[i] * unit);
    }
    out.color = color;
    return out;
  };
  PlotSeries record{"record: means of " + std::to_string(b.record.size()) + " blocks of " + Short(b.block_s) + " s",
                    PlotStyle::kPoints, b.time_s, {}};
  for (double r : b.record) record.y.push_back(r * unit);
  record.color = "#000000";
  PlotSeries baseline{"baseline", PlotStyle::kDashedLine, b.time_s, leveled(b.baseline_path)};
  baseline.color = kBaselineColor;
  // The verdict's filled band under the baseline's outline, then the record and the levels.
  if (!b.verdict_path.empty() && b.verdict_sd.size() == b.verdict_path.size()) {
    plot.series.push_back(band(leveled(b.verdict_path), b.verdict_sd, ModelName(s), PlotStyle::kBand, kModelColor));
  }
  if (b.baseline_sd.size() == b.baseline_path.size()) {
    plot.series.push_back(band(baseline.y, b.baseline_sd, "baseline", PlotStyle::kBandOutline, kBaselineColor));
  }
  plot.series.push_back(record);
  plot.series.push_back(baseline);
  if (!b.verdict_path.empty()) {
    PlotSeries model{ModelName(s), PlotStyle::kLine, b.time_s, leveled(b.verdict_path)};
    model.color = kModelColor;
    plot.series.push_back(model);
  }
  std::string where;
  bool step = false, settling = false;  // one mark per view: its first region
  for (const GapRegion& r : s.regions) {
    if (r.view == View::kChangePoint && !step) {
      step = true;
      where += std::string(where.empty() ? "" : "; ") + "level " + (r.mean_z > 0 ? "rises" : "falls") + " at t = " +
               Short(r.time_s) + " s";
      PlotSpan span{r.time_s, r.time_s, kGapColor, 0.45, "located step"};
      span.height = kStrip;
      plot.spans.push_back(span);
    } else if (r.view == View::kTrend && !settling) {
      settling = true;
      where += std::string(where.empty() ? "" : "; ") + "settles " + (r.mean_z > 0 ? "from above" : "from below") +
               ", time constant " + Short(r.time_s) + " s";
      PlotSpan span{0.0, std::min(r.time_s, b.time_s.empty() ? r.time_s : b.time_s.back()), kGapColor, 0.45,
                    "settling: one time constant from the start"};
      span.height = kStrip;
      plot.spans.push_back(span);
    }
  }
  plot.title = "block means over the record" + (where.empty() ? "" : ": " + where);
  return plot;
}

}  // namespace

std::vector<AllanPlot> DiagnosePanels(const DiagnosisSummary& s, const std::string& title,
                                      const DiagnoseUnits& units) {
  std::vector<AllanPlot> panels = {AllanPanel(s, title, units)};
  std::vector<View> shown;
  bool block_means = false;
  for (const GapRegion& r : s.regions) {
    if (r.view == View::kOavar || std::find(shown.begin(), shown.end(), r.view) != shown.end()) continue;
    shown.push_back(r.view);
    if (TauView(r.view)) {
      panels.push_back(ViewPanel(s, r.view));
    } else if (!block_means && !s.block_means.record.empty()) {
      block_means = true;
      panels.push_back(BlockMeansPanel(s, units));
    }
  }
  return panels;
}

}  // namespace allanlab::app
