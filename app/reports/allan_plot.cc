#include "app/reports/allan_plot.h"

#include <fcntl.h>
#include <spawn.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <vector>

#include "app/reports/provenance.h"
#include "common/gnuplot.h"
#include "common/number_text.h"

namespace allanlab::app {
namespace {

// A log axis from lo to hi within three decades gets 2 and 5 of each decade labelled too: gnuplot
// labels decades only, and accelerometer curves between 0.2 and 5 mg carried the one label "1".
std::string ExtraLogTics(const char* axis, double lo, double hi) {
  if (!(lo > 0) || !(hi < 1000 * lo)) return "";
  std::string extra;
  for (int k = static_cast<int>(std::floor(std::log10(lo))); k <= static_cast<int>(std::ceil(std::log10(hi))); ++k) {
    for (double d : {2.0, 5.0}) {
      const double v = d * std::pow(10.0, k);
      if (v >= lo && v <= hi) extra += (extra.empty() ? "" : ", ") + ShortestDecimal(v);
    }
  }
  return extra.empty() ? "" : "set " + std::string(axis) + "tics add (" + extra + ")\n";
}


bool Fail(std::string* why, const std::string& message) {
  if (why) *why = message;
  return false;
}

// A point the plot's axes can show: finite, and positive on a log axis.
bool Plottable(const AllanPlot& plot, double x, double y) {
  return std::isfinite(x) && std::isfinite(y) && (x > 0 || !plot.log_x) && (y > 0 || !plot.log_y);
}

bool HasBars(const PlotSeries& s) {
  return (s.style == PlotStyle::kPoints || s.style == PlotStyle::kBand || s.style == PlotStyle::kBandOutline) &&
         s.y_low.size() == s.x.size() && s.y_high.size() == s.x.size();
}

std::string SlopeLabel(double slope) {
  if (slope == 0.0) return "0";
  const std::string sign = slope > 0 ? "+" : "-";
  const double magnitude = std::abs(slope);
  if (magnitude == std::round(magnitude)) return sign + ShortestDecimal(magnitude);
  if (2 * magnitude == std::round(2 * magnitude)) {
    return sign + ShortestDecimal(2 * magnitude) + "/2";
  }
  return sign + ShortestDecimal(magnitude);
}

const char* Color(std::size_t index) {
  static const char* const kColors[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e",
                                        "#9467bd", "#8c564b", "#e377c2", "#17becf"};
  return kColors[index % (sizeof kColors / sizeof kColors[0])];
}

std::string TerminalLines(int width_px, int height_px, const std::string& output_path) {
  std::ostringstream os;
  os << "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n"
     << "  set terminal pngcairo noenhanced size " << width_px << "," << height_px
     << " font ',10'\n"
     << "} else {\n"
     << "  set terminal png noenhanced size " << width_px << "," << height_px << "\n"
     << "}\n"
     << "set output " << GnuplotQuoted(output_path) << "\n";
  return os.str();
}

// The commands that draw one diagram (after the terminal is set).
std::string Body(const AllanPlot& plot) {
  // A linear y axis shows zero and negative values; a log one only positive ones.
  const auto Plottable = [&](double x, double y) { return allanlab::app::Plottable(plot, x, y); };
  std::vector<const PlotSeries*> kept;
  std::vector<std::vector<std::pair<double, double>>> points;
  std::vector<std::vector<std::pair<double, double>>> bars;  // (low, high) per kept point
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = 0;
  double y_lo = std::numeric_limits<double>::infinity(), y_hi = 0;
  int guide_index = -1;  // into points
  for (std::size_t s = 0; s < plot.series.size(); ++s) {
    const PlotSeries& series = plot.series[s];
    std::vector<std::pair<double, double>> valid, valid_bars;
    const bool band = series.style == PlotStyle::kBand || series.style == PlotStyle::kBandOutline;
    if (band && !HasBars(series)) continue;
    for (std::size_t i = 0; i < std::min(series.x.size(), series.y.size()); ++i) {
      if (!Plottable(series.x[i], series.y[i])) continue;
      if (band && !(Plottable(series.x[i], series.y_low[i]) && Plottable(series.x[i], series.y_high[i]))) {
        continue;
      }
      valid.emplace_back(series.x[i], series.y[i]);
      x_lo = std::min(x_lo, series.x[i]);
      x_hi = std::max(x_hi, series.x[i]);
      y_lo = std::min(y_lo, series.y[i]);
      y_hi = std::max(y_hi, series.y[i]);
      if (HasBars(series)) {
        const double low = Plottable(series.x[i], series.y_low[i]) ? series.y_low[i] : series.y[i];
        const double high =
            Plottable(series.x[i], series.y_high[i]) ? series.y_high[i] : series.y[i];
        valid_bars.emplace_back(low, high);
        y_lo = std::min(y_lo, low);
        y_hi = std::max(y_hi, high);
      }
    }
    if (valid.empty()) continue;
    kept.push_back(&series);
    points.push_back(std::move(valid));
    bars.push_back(std::move(valid_bars));
    if (static_cast<int>(s) == plot.guide_series) guide_index = static_cast<int>(points.size()) - 1;
  }
  // Guides must not stretch the axes, so the ranges come from the data alone.
  if (x_hi <= x_lo) x_hi = plot.log_x ? x_lo * 2 : x_lo + 1;
  for (double y : plot.y_lines) {
    if (!plot.log_y && std::isfinite(y)) y_lo = std::min(y_lo, y), y_hi = std::max(y_hi, y);
  }
  if (y_hi <= y_lo) y_hi = plot.log_y ? y_lo * 2 : y_lo + 1;
  const double y_pad = 0.08 * (y_hi - y_lo);
  std::ostringstream os;
  os << "set title " << GnuplotQuoted(plot.title) << "\n"
     << "set xlabel " << GnuplotQuoted(plot.x_label) << "\n"
     << "set ylabel " << GnuplotQuoted(plot.y_label) << "\n"
     << (plot.log_x ? "set logscale x\n" : "unset logscale x\n")
     << (plot.log_y ? "set logscale y\n" : "unset logscale y\n")
     << "set format x '%g'\nset format y '%g'\n"
     << "set grid xtics ytics mxtics mytics lc rgb '#e8e8e8' lw 1\n"
     << "set key " << plot.key << "\n"
     << "set samples 200\n"
     << "set xrange [" << ShortestDecimal(plot.log_x ? x_lo / 1.5 : x_lo - 0.03 * (x_hi - x_lo)) << ":"
     << ShortestDecimal(plot.log_x ? x_hi * 1.5 : x_hi + 0.03 * (x_hi - x_lo)) << "]\n";
  if (plot.log_x) os << ExtraLogTics("x", x_lo / 1.5, x_hi * 1.5);
  if (plot.log_y) {
    os << "set yrange [" << ShortestDecimal(y_lo / 2) << ":" << ShortestDecimal(y_hi * 2) << "]\n";
    os << ExtraLogTics("y", y_lo / 2, y_hi * 2);
  } else {
    os << "set yrange [" << ShortestDecimal(y_lo - y_pad) << ":" << ShortestDecimal(y_hi + y_pad) << "]\n";
  }
  for (double y : plot.y_lines) {
    if (std::isfinite(y)) {
      os << "set arrow from graph 0, first " << ShortestDecimal(y) << " to graph 1, first " << ShortestDecimal(y)
         << " nohead lc rgb '#999999' dt 2\n";
    }
  }
  // Spans: rectangles behind the curves, each with a dummy keyed clause when titled (objects
  // have no key entry of their own).
  std::vector<std::string> span_keys;
  for (std::size_t i = 0; i < plot.spans.size(); ++i) {
    const PlotSpan& span = plot.spans[i];
    if (!((span.x_min > 0 || !plot.log_x) && std::isfinite(span.x_min)) || !(span.x_max >= span.x_min) ||
        !std::isfinite(span.x_max)) {
      continue;
    }
    // A one-point span gets a width of a factor 1.05 each way on a log axis, 0.5 % of the range
    // on a linear one.
    const double half = 0.005 * (x_hi - x_lo);
    const double lo = span.x_min == span.x_max ? (plot.log_x ? span.x_min / 1.05 : span.x_min - half) : span.x_min;
    const double hi = span.x_min == span.x_max ? (plot.log_x ? span.x_max * 1.05 : span.x_max + half) : span.x_max;
    const double opacity = std::clamp(span.opacity, 0.0, 1.0);
    os << "set object " << i + 1 << " rect from " << ShortestDecimal(lo) << ", graph 0 to "
       << ShortestDecimal(hi) << ", graph " << ShortestDecimal(std::clamp(span.height, 0.0, 1.0))
       << " behind fc rgb " << GnuplotQuoted(span.color)
       << " fs transparent solid " << ShortestDecimal(opacity) << " noborder\n";
    if (!span.title.empty() &&
        std::find(span_keys.begin(), span_keys.end(), span.title) == span_keys.end()) {
      span_keys.push_back(span.title);
      span_keys.push_back(span.color);
      span_keys.push_back(ShortestDecimal(opacity));
    }
  }
  for (std::size_t s = 0; s < points.size(); ++s) {
    os << "$s" << s << " << EOD\n";
    for (std::size_t i = 0; i < points[s].size(); ++i) {
      os << ShortestDecimal(points[s][i].first) << " " << ShortestDecimal(points[s][i].second);
      if (!bars[s].empty()) {
        os << " " << ShortestDecimal(bars[s][i].first) << " " << ShortestDecimal(bars[s][i].second);
      }
      os << "\n";
    }
    os << "EOD\n";
  }
  std::vector<std::string> clauses;
  if (guide_index >= 0) {
    for (std::size_t g = 0; g < plot.slope_guides.size(); ++g) {
      const double slope = plot.slope_guides[g];
      // log y = c + slope log x with c the smallest intercept over the points: the line touches
      // the curve at one point and stays below it elsewhere.
      double best = std::numeric_limits<double>::infinity();
      double touch_x = 0, touch_y = 0;
      for (const auto& [x, y] : points[guide_index]) {
        const double c = std::log(y) - slope * std::log(x);
        if (c < best) {
          best = c;
          touch_x = x;
          touch_y = y;
        }
      }
      os << "g" << g << "(x) = " << ShortestDecimal(std::exp(best)) << " * x**("
         << ShortestDecimal(slope) << ")\n";
      // Guides often share a touching point (a curve end), so each label sits on its own line a
      // factor 3 in tau away from it, towards the inside of the plot, just under the line.
      const double label_x = touch_x * 3 <= x_hi ? touch_x * 3 : touch_x / 3;
      const double label_y = touch_y * std::pow(label_x / touch_x, slope) / 1.3;
      if (label_y > y_lo / 2 && label_y < y_hi * 2) {
        os << "set label " << g + 1 << " " << GnuplotQuoted(SlopeLabel(slope)) << " at "
           << ShortestDecimal(label_x) << "," << ShortestDecimal(label_y)
           << " center textcolor rgb '#909090' font ',8'\n";
      }
      clauses.push_back("g" + std::to_string(g) + "(x) with lines lc rgb '#b8b8b8' dt 3 notitle");
    }
  }
  for (std::size_t s = 0; s < kept.size(); ++s) {
    std::string style;
    switch (kept[s]->style) {
      case PlotStyle::kPoints:
        style = bars[s].empty() ? "using 1:2 with points pt 7 ps 1.1"
                                : "using 1:2:3:4 with yerrorbars pt 7 ps 1.1";
        break;
      case PlotStyle::kLine:
        style = "using 1:2 with lines lw 2";
        break;
      case PlotStyle::kDashedLine:
        style = "using 1:2 with lines lw 1.5 dt 2";
        break;
      case PlotStyle::kBand:
        style = "using 1:3:4 with filledcurves fs transparent solid 0.25 noborder";
        break;
      case PlotStyle::kBandOutline:
        style = "using 1:3 with lines lw 1 dt 3";
        break;
    }
    const std::string color = kept[s]->color.empty() ? Color(s) : kept[s]->color;
    if (kept[s]->style == PlotStyle::kBandOutline) {  // the upper edge, keyed with the lower one
      clauses.push_back("$s" + std::to_string(s) + " using 1:4 with lines lw 1 dt 3 lc rgb " + GnuplotQuoted(color) +
                        " notitle");
    }
    clauses.push_back("$s" + std::to_string(s) + " " + style + " lc rgb " + GnuplotQuoted(color) + " title " +
                      GnuplotQuoted(kept[s]->title));
  }
  for (std::size_t k = 0; k + 2 < span_keys.size(); k += 3) {
    // NaN draws nothing but puts the span's colour in the key.
    clauses.push_back("NaN with filledcurves fs transparent solid " + span_keys[k + 2] +
                      " noborder fc rgb " + GnuplotQuoted(span_keys[k + 1]) + " title " + GnuplotQuoted(span_keys[k]));
  }
  os << "plot ";
  for (std::size_t i = 0; i < clauses.size(); ++i) {
    os << (i ? ", \\\n     " : "") << clauses[i];
  }
  os << "\n";
  return os.str();
}

std::string Script(const AllanPlot& plot, const std::string& output_path) {
  return TerminalLines(plot.width_px, plot.height_px, output_path) + Body(plot) + "unset output\n";
}

// Rows of a panel's key when it sits below the axes, at two entries a row (what gnuplot put in
// diagnose's 900 px panels; more a row only leaves room to spare): series with a title, and spans
// with distinct titles. 0: no key below.
int BelowKeyRows(const AllanPlot& p) {
  if (p.key.rfind("below", 0) != 0) return 0;
  std::set<std::string> span_titles;
  for (const PlotSpan& span : p.spans) {
    if (!span.title.empty()) span_titles.insert(span.title);
  }
  int entries = static_cast<int>(span_titles.size());
  for (const PlotSeries& series : p.series) entries += series.title.empty() ? 0 : 1;
  return (entries + 1) / 2;
}

bool AnyPlottable(const AllanPlot& plot) {
  for (const PlotSeries& s : plot.series) {
    for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (Plottable(plot, s.x[i], s.y[i])) {
        return true;
      }
    }
  }
  return false;
}

}  // namespace

std::string AllanPlotGridScript(const std::vector<AllanPlot>& panels, int columns, const std::string& output_path) {
  columns = std::clamp(columns, 1, static_cast<int>(panels.size()));
  const int rows = (static_cast<int>(panels.size()) + columns - 1) / columns;
  int width = 0, height = 0;
  for (const AllanPlot& p : panels) {
    width = std::max(width, p.width_px);
    height = std::max(height, p.height_px);
  }
  std::string out = TerminalLines(width * columns, height * rows, output_path);
  out += "set multiplot layout " + std::to_string(rows) + "," + std::to_string(columns) + "\n";
  // In a multiplot gnuplot leaves a key below the axes one row too little room when it wraps,
  // and the x label then lies over the key's first row: one bottom margin (in character heights:
  // tic labels and x label, then the key's rows; 2.5 and 1.3 set by eye on the simulated drift
  // record's and imu1 Gyro_X's plots) for every panel, so their axes also line up.
  int key_rows = 0;
  for (const AllanPlot& p : panels) key_rows = std::max(key_rows, BelowKeyRows(p));
  if (key_rows > 0) out += "set bmargin " + ShortestDecimal(2.5 + 1.3 * key_rows) + "\n";
  for (const AllanPlot& p : panels) out += Body(p) + "unset object\nunset label\nunset arrow\n";
  return out + "unset multiplot\nunset output\n";
}

namespace {

// Runs gnuplot on `text`, which writes png->temp_path().
bool RunGnuplotInto(const std::string& text, AtomicFile* png, std::string* why) {
  png->stream().close();
  return RunGnuplot(text, why) && GnuplotWroteImage(png->temp_path(), why);
}

}  // namespace

bool RenderAllanPlot(const AllanPlot& plot, AtomicFile* png, std::string* why) {
  if (!png || !png->is_open()) return Fail(why, "internal error: plot output not open");
  if (!AnyPlottable(plot)) return Fail(why, "nothing to plot: no positive, finite point in any series");
  return RunGnuplotInto(Script(plot, png->temp_path()), png, why);
}

bool RenderAllanPlotGrid(const std::vector<AllanPlot>& panels, int columns, AtomicFile* png, std::string* why) {
  if (panels.size() == 1) return RenderAllanPlot(panels.front(), png, why);
  if (!png || !png->is_open()) return Fail(why, "internal error: plot output not open");
  if (panels.empty()) return Fail(why, "nothing to plot: no panel");
  for (const AllanPlot& p : panels) {
    if (!AnyPlottable(p)) return Fail(why, "nothing to plot in panel '" + p.title + "': no positive, finite point");
  }
  return RunGnuplotInto(AllanPlotGridScript(panels, columns, png->temp_path()), png, why);
}

bool RenderAllanPlots(const std::vector<AllanPlot>& panels, AtomicFile* png, std::string* why) {
  return RenderAllanPlotGrid(panels, static_cast<int>(panels.size()), png, why);
}

bool WriteAllanPlotPng(const AllanPlot& plot, const std::string& png_path, std::string* why) {
  AtomicFile png;
  return png.Open(png_path, why) && RenderAllanPlot(plot, &png, why) && png.Commit(why);
}

}  // namespace allanlab::app
