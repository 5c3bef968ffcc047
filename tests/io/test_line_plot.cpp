// Line plots: the frame spans the data, markers land where the frame maps the points.
#include <gtest/gtest.h>

#include <cmath>

#include "quadtri/io/line_plot.h"
#include "quadtri/math/error.h"

namespace quadtri::testing {
namespace {

TEST(LinePlot, LogFrameSpansWholeDecadesAroundTheData) {
  const std::vector<PlotSeries> series = {{"a", {1, 0, 0}, {{20, 0.8}, {81920, 1.6}}}};
  const PlotFrame f = plotFrame(series, PlotOptions{});
  EXPECT_EQ(f.x0, 1.0);
  EXPECT_EQ(f.x1, 5.0);
  EXPECT_NEAR(f.y1, 1.15 * 1.6, 1e-12);
  // Decades are evenly spaced: 10 and 1000 sit at the ends of the first and third quarter.
  const int x10 = f.toPixel(10, 0).first, x1000 = f.toPixel(1000, 0).first;
  const int x1e5 = f.toPixel(1e5, 0).first;
  EXPECT_EQ(x10, f.left);
  EXPECT_EQ(x1e5, f.right);
  EXPECT_NEAR(x1000, (f.left + f.right) / 2.0, 1.0);
  EXPECT_EQ(f.toPixel(10, 0).second, f.bottom);
}

TEST(LinePlot, MarkersAreDrawnInTheSeriesColourAtTheirPoints) {
  const Rgb red{1, 0, 0}, blue{0, 0, 1};
  const std::vector<PlotSeries> series = {
      {"implicit / shading", red, {{20, 1.1}, {320, 1.2}, {5120, 1.3}}},
      {"implicit / param", blue, {{20, 0.5}, {320, 0.4}, {5120, 0.3}}}};
  const PlotOptions options;
  const Canvas plot = linePlot(series, options);
  ASSERT_EQ(plot.width(), options.width);
  ASSERT_EQ(plot.height(), options.height);
  const PlotFrame f = plotFrame(series, options);
  for (const PlotSeries& s : series)
    for (const auto& [x, y] : s.points) {
      const auto [px, py] = f.toPixel(x, y);
      EXPECT_EQ(plot.get(px, py), s.color) << s.label << " at " << x;
    }
  // Far from every series, inside the frame, the background stays white.
  const auto [qx, qy] = f.toPixel(2000, 0.8);
  EXPECT_EQ(plot.get(qx, qy), (Rgb{1, 1, 1}));
}

TEST(LinePlot, LogLogFrameAndMarkersOfEveryShape) {
  const Rgb red{1, 0, 0}, blue{0, 0, 1};
  const std::vector<PlotSeries> series = {
      {"a", red, {{20, 0.05}, {320, 3e-3}, {5120, 2e-4}}, Marker::Circle},
      {"", blue, {{64, 0.02}, {1024, 1e-3}}, Marker::Triangle},
      {"", red, {{100, 1e-5}}, Marker::Cross}};
  PlotOptions options;
  options.logY = true;
  options.legendWidth = 200;
  options.markerLegend = {{"sphere", Marker::Circle}, {"torus", Marker::Triangle}};
  const PlotFrame f = plotFrame(series, options);
  EXPECT_EQ(f.y0, -5.0);
  EXPECT_EQ(f.y1, -1.0);
  EXPECT_EQ(f.right, options.width - 24 - 200);
  EXPECT_EQ(f.toPixel(10, 1e-5).second, f.bottom);
  EXPECT_EQ(f.toPixel(10, 0.1).second, f.top);
  EXPECT_NEAR(f.toPixel(10, 1e-3).second, (f.top + f.bottom) / 2.0, 1.0);
  const Canvas plot = linePlot(series, options);
  for (const PlotSeries& s : series)
    for (const auto& [x, y] : s.points) {
      const auto [px, py] = f.toPixel(x, y);
      EXPECT_EQ(plot.get(px, py), s.color) << x;
    }
  EXPECT_THROW(plotFrame({{"zero", red, {{10, 0.0}}}}, options), Error);
}

TEST(LinePlot, RejectsPointsItCannotDraw) {
  EXPECT_THROW(plotFrame({{"bad", {0, 0, 0}, {{0.0, 1.0}}}}, PlotOptions{}), Error);
  EXPECT_THROW(plotFrame({{"nan", {0, 0, 0}, {{1.0, std::nan("")}}}}, PlotOptions{}), Error);
  EXPECT_THROW(plotFrame({}, PlotOptions{}), Error);
}

}  // namespace
}  // namespace quadtri::testing
