#include "app/reports/allan_plot.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/support/read_file.h"

namespace allanlab::app {
namespace {

namespace fs = std::filesystem;

using testing_support::ReadAll;

AllanPlot WhiteNoisePlot() {
  AllanPlot plot;
  plot.title = "white noise, seed 'quoted'";
  PlotSeries line{"exact", PlotStyle::kLine, {}, {}};
  PlotSeries points{"simulated", PlotStyle::kPoints, {}, {}};
  for (double tau = 0.01; tau < 100; tau *= 2) {
    line.x.push_back(tau);
    line.y.push_back(0.1 / std::sqrt(tau));
    points.x.push_back(tau);
    points.y.push_back(0.1 / std::sqrt(tau) * (1 + 0.05 * std::sin(tau)));
  }
  points.x.push_back(1.0);
  points.y.push_back(0.0);  // not drawable on a log axis: skipped, not an error
  plot.series = {line, points};
  return plot;
}

class AllanPlotTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string templ = (fs::path(::testing::TempDir()) / "allan_plot_test.XXXXXX").string();
    ASSERT_NE(::mkdtemp(templ.data()), nullptr);
    dir_ = templ;
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(AllanPlotTest, WritesAPng) {
  std::string why;
  if (!FindGnuplot(&why)) GTEST_SKIP() << why;
  ASSERT_TRUE(WriteAllanPlotPng(WhiteNoisePlot(), (dir_ / "plot.png").string(), &why)) << why;
  const std::string png = ReadAll(dir_ / "plot.png");
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
}

TEST_F(AllanPlotTest, PointsWithErrorBarsIncludingOneSidedOnes) {
  std::string why;
  if (!FindGnuplot(&why)) GTEST_SKIP() << why;
  AllanPlot plot = WhiteNoisePlot();
  PlotSeries& points = plot.series[1];
  for (std::size_t i = 0; i < points.x.size(); ++i) {
    points.y_low.push_back(i == 2 ? 0.0 : points.y[i] * 0.9);  // 0: no lower bar on a log axis
    points.y_high.push_back(i == 3 ? NAN : points.y[i] * 1.2);
  }
  ASSERT_TRUE(WriteAllanPlotPng(plot, (dir_ / "bars.png").string(), &why)) << why;
  EXPECT_EQ(ReadAll(dir_ / "bars.png").substr(1, 3), "PNG");
}

// A time-domain panel: linear axes (negative rates, a time axis from 0), a band drawn as its
// outline, and strips along the x axis (a one-point one too).
TEST_F(AllanPlotTest, LinearAxesBandOutlinesAndStripsRender) {
  std::string why;
  if (!FindGnuplot(&why)) GTEST_SKIP() << why;
  AllanPlot plot;
  plot.title = "block means";
  plot.log_x = plot.log_y = false;
  plot.guide_series = -1;
  PlotSeries means{"record", PlotStyle::kPoints, {}, {}};
  PlotSeries band{"95 % band", PlotStyle::kBandOutline, {}, {}};
  for (int k = 0; k < 64; ++k) {
    const double t = 10.0 * k, level = k < 40 ? -3.0 : 12.0;
    means.x.push_back(t);
    means.y.push_back(level + std::sin(k));
    band.x.push_back(t);
    band.y.push_back(level);
    band.y_low.push_back(level - 2.0);
    band.y_high.push_back(level + 2.0);
  }
  plot.series = {band, means};
  PlotSpan step{400.0, 400.0, "#d62728", 0.45, "located step"};
  step.height = 0.035;
  PlotSpan settling{0.0, 120.0, "#d62728", 0.45, "settling"};
  settling.height = 0.035;
  plot.spans = {step, settling};
  ASSERT_TRUE(WriteAllanPlotPng(plot, (dir_ / "linear.png").string(), &why)) << why;
  const std::string png = ReadAll(dir_ / "linear.png");
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
}

TEST_F(AllanPlotTest, MissingGnuplotFailsClearlyAndKeepsTheOldFile) {
  { std::ofstream(dir_ / "plot.png") << "old"; }
  const std::string saved_path = std::getenv("PATH") ? std::getenv("PATH") : "";
  ::setenv("PATH", (dir_ / "empty_bin").string().c_str(), 1);
  std::string find_why, write_why;
  const bool found = FindGnuplot(&find_why);
  const bool wrote = WriteAllanPlotPng(WhiteNoisePlot(), (dir_ / "plot.png").string(), &write_why);
  ::setenv("PATH", saved_path.c_str(), 1);
  EXPECT_FALSE(found);
  EXPECT_NE(find_why.find("gnuplot"), std::string::npos) << find_why;
  EXPECT_FALSE(wrote);
  EXPECT_NE(write_why.find("gnuplot"), std::string::npos) << write_why;
  EXPECT_EQ(ReadAll(dir_ / "plot.png"), "old");
  int entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_)) ++entries;
  EXPECT_EQ(entries, 1) << "a temporary was left behind";
}

TEST_F(AllanPlotTest, NothingDrawableIsAnErrorAndWritesNothing) {
  AllanPlot plot;
  plot.series = {PlotSeries{"empty", PlotStyle::kLine, {1.0, 2.0}, {0.0, -1.0}}};
  std::string why;
  EXPECT_FALSE(WriteAllanPlotPng(plot, (dir_ / "plot.png").string(), &why));
  EXPECT_FALSE(why.empty());
  EXPECT_FALSE(fs::exists(dir_ / "plot.png"));
}

// Panels with their key below the axes get one bottom margin that holds the largest key (at two
// entries a row): without it gnuplot put the x label of diagnose's block-mean panel (7 entries)
// over the key's first row. Keys elsewhere leave gnuplot's margins alone.
TEST(AllanPlotGridScriptTest, KeysBelowTheAxesShareABottomMarginForTheLargest) {
  AllanPlot small = WhiteNoisePlot(), large = WhiteNoisePlot();
  small.key = large.key = "below left horizontal";
  for (int i = 0; i < 5; ++i) large.series.push_back(PlotSeries{"extra " + std::to_string(i), PlotStyle::kLine, {1.0}, {1.0}});
  large.spans = {PlotSpan{1.0, 2.0, "#d62728", 0.4, "gap"}, PlotSpan{3.0, 4.0, "#d62728", 0.4, "gap"}};
  // small: 2 entries, 1 row; large: 7 series + 1 span title = 8 entries, 4 rows: 2.5 + 1.3 x 4.
  const std::string both = AllanPlotGridScript({small, large}, 2, "out.png");
  EXPECT_NE(both.find("set bmargin 7.7\n"), std::string::npos) << both.substr(0, 400);
  EXPECT_EQ(both.find("set bmargin", both.find("set bmargin") + 1), std::string::npos);
  EXPECT_NE(AllanPlotGridScript({small, small}, 2, "out.png").find("set bmargin 3.8\n"), std::string::npos);
  EXPECT_EQ(AllanPlotGridScript({WhiteNoisePlot(), WhiteNoisePlot()}, 2, "out.png").find("bmargin"), std::string::npos);
}

}  // namespace
}  // namespace allanlab::app
