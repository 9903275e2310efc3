#include "app/reports/diagnose_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "experiments/diagnosis/envelope.h"

namespace allanlab::app {
namespace {

using namespace allanlab::experiments;

constexpr const char* kBaselineColor = "#1f77b4";
constexpr const char* kModelColor = "#2ca02c";
constexpr const char* kGapColor = "#d62728";
constexpr const char* kKey = "below left horizontal";  // under the axes: never over a curve

std::string Short(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", v);
  return buffer;
}

const ViewResiduals* Find(const std::vector<ViewResiduals>& views, View v) {
  for (const ViewResiduals& r : views) {
    if (r.view == v) return &r;
  }
  return nullptr;
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
  auto band = [&](const sim::SensorModel& model, const std::string& name, const std::string& color,
                  PlotSeries* line) {
    const OavarTheory t = ExactOavar(model, s.curve.m, s.num_samples);
    PlotSeries b{name + ": 95 % band", PlotStyle::kBand, s.curve.tau_s, adev(t.mean)};
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
  plot.series.push_back(band(s.baseline_model, "baseline", kBaselineColor, &baseline_line));
  if (s.verdict_candidate >= 0) {
    plot.series.push_back(band(s.candidates[s.verdict_candidate].model, ModelName(s), kModelColor, &model_line));
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
    case View::kChangePoint: return "block means: largest step";
    case View::kTrend: return "block means: exponential settling";
  }
  return "?";
}

std::string AxisLabel(View v) {
  if (v == View::kPsd) return "frequency [Hz]";
  if (v == View::kChangePoint || v == View::kTrend) return "block length [s]";
  return "tau [s]";
}

// One view: z of the record against the baseline and against the verdict model, with 0 and the
// gap level +-threshold.
AllanPlot ViewPanel(const DiagnosisSummary& s, View v, const std::string& where) {
  AllanPlot plot;
  plot.title = std::string(ViewId(v)) + ": " + ViewTitle(v) + where;
  plot.x_label = AxisLabel(v);
  plot.y_label = "standardised residual z";
  plot.log_y = false;
  plot.key = kKey;
  plot.guide_series = -1;
  plot.slope_guides.clear();
  plot.y_lines = {-s.threshold, 0.0, s.threshold};
  plot.height_px = 450;
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

}  // namespace

std::vector<AllanPlot> DiagnosePanels(const DiagnosisSummary& s, const std::string& title,
                                      const DiagnoseUnits& units) {
  std::vector<AllanPlot> panels = {AllanPanel(s, title, units)};
  std::vector<View> shown;
  for (const GapRegion& r : s.regions) {
    if (r.view == View::kOavar || std::find(shown.begin(), shown.end(), r.view) != shown.end()) continue;
    shown.push_back(r.view);
    std::string where;
    if (r.view == View::kChangePoint) where = " (step at t = " + Short(r.time_s) + " s)";
    if (r.view == View::kTrend) where = " (time constant " + Short(r.time_s) + " s)";
    panels.push_back(ViewPanel(s, r.view, where));
  }
  return panels;
}

}  // namespace allanlab::app
