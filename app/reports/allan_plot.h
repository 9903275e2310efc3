#pragma once
// A log-log Allan diagram rendered to PNG by gnuplot: any number of series (points, lines, dashed
// lines) plus faint slope guides. Reusable by every command that draws Allan curves.
#include <string>
#include <vector>

#include "common/atomic_file.h"
#include "common/gnuplot.h"

namespace allanlab::app {

// kBand: a translucent filled area between y_low and y_high (an envelope or confidence band);
// y is its centre, used for the axis ranges only. kBandOutline: the same band drawn as its two
// edges (thin dotted lines), so that a filled band under it stays visible.
enum class PlotStyle { kPoints, kLine, kDashedLine, kBand, kBandOutline };

struct PlotSeries {
  std::string title;  // key entry
  PlotStyle style = PlotStyle::kLine;
  std::vector<double> x;  // tau [s]
  std::vector<double> y;  // same length as x, in the unit of AllanPlot::y_label
  // Optional vertical error bars (e.g. confidence intervals), kPoints only: when both have the
  // length of x, each point gets a bar from y_low to y_high. An end a log axis cannot show (<= 0,
  // NaN, inf) is drawn at the point itself, so a one-sided bar stays one-sided. kBand needs both
  // (its lower and upper edge; points with an edge a log axis cannot show are skipped).
  std::vector<double> y_low = {};
  std::vector<double> y_high = {};
  std::string color = {};  // gnuplot colour ('#rrggbb'); empty: the palette colour of its index
};

// A shaded stretch of the x axis over the whole height (e.g. where a record leaves its model).
struct PlotSpan {
  double x_min = 0.0, x_max = 0.0;  // x_min == x_max: a thin span around one point
  std::string color = "#ff7f0e";    // gnuplot colour name or '#rrggbb'
  double opacity = 0.15;            // 0..1
  std::string title;                // key entry ("" : none); spans with the same title share it
  double height = 1.0;              // from the bottom, as a fraction of the graph's height (a strip
                                    // along the x axis that hides no data: 0.04)
};

struct AllanPlot {
  std::string title;
  std::string x_label = "tau [s]";
  std::string y_label = "Allan deviation [deg/h]";
  // Drawn in order, later ones on top. Points that a log axis cannot show (<= 0, NaN, inf) are
  // skipped; a series left empty is dropped.
  std::vector<PlotSeries> series;
  // Drawn behind the series, in order.
  std::vector<PlotSpan> spans;
  // Log-log slopes of the faint guide lines. Each guide is the line of that slope that touches
  // series[guide_series] from below (the tangent of the slope method, IEEE 952 Annex C), so a
  // guide hugs the curve where that noise type dominates. guide_series < 0: no guides.
  std::vector<double> slope_guides = {-1.0, -0.5, 0.0, 0.5, 1.0};
  int guide_series = 0;
  bool log_y = true;                     // false: a linear y axis (e.g. standardised residuals)
  bool log_x = true;                     // false: a linear x axis (e.g. time in the record)
  std::string key = "top right opaque";  // gnuplot key placement ("outside right top", ...)
  std::vector<double> y_lines = {};      // faint horizontal reference lines (e.g. +-threshold)
  int width_px = 900;
  int height_px = 650;
};

// Renders `plot` with gnuplot (pngcairo terminal when available, else png) into png->temp_path().
// `png` must be open; the caller commits it (with the command's other outputs) or discards it.
// Fails with gnuplot's first error line when gnuplot is missing, fails, or writes nothing.
bool RenderAllanPlot(const AllanPlot& plot, AtomicFile* png, std::string* why);

// Several diagrams side by side in one PNG (e.g. an IMU's gyro and accelerometer axes, whose
// units differ), each `width_px` wide; one panel is RenderAllanPlot.
bool RenderAllanPlots(const std::vector<AllanPlot>& panels, AtomicFile* png, std::string* why);

// Panels in a grid of `columns` (rows filled left to right), each `width_px` x `height_px`.
bool RenderAllanPlotGrid(const std::vector<AllanPlot>& panels, int columns, AtomicFile* png, std::string* why);
// The gnuplot script RenderAllanPlotGrid runs for two or more panels, writing the image to
// `output_path`. Panels whose key sits below the axes ("below ...") share one bottom margin that
// holds the largest such key at two entries a row: gnuplot's own leaves a wrapped key one row
// short in a multiplot, and the x label then lies over it.
std::string AllanPlotGridScript(const std::vector<AllanPlot>& panels, int columns, const std::string& output_path);

// RenderAllanPlot into a file of its own: on any failure, no file at `png_path` is created or
// changed.
bool WriteAllanPlotPng(const AllanPlot& plot, const std::string& png_path, std::string* why);

}  // namespace allanlab::app
