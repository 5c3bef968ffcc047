// Line plots drawn on a Canvas: the render-time ratios of the thesis' figure 5.5.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "quadtri/io/canvas.h"

namespace quadtri {

/// How a series marks its points.
enum class Marker { Square, Circle, Triangle, Cross };

struct PlotSeries {
  std::string label;  ///< legend entry; empty: the series has none
  Rgb color;
  std::vector<std::pair<double, double>> points;  ///< (x, y), > 0 on a log axis
  Marker marker = Marker::Square;
};

struct PlotOptions {
  int width = 720, height = 440;
  std::string title, xLabel, yLabel;
  bool logX = true;
  bool logY = false;
  /// > 0: the legend goes in a column this wide right of the frame instead of inside it.
  int legendWidth = 0;
  /// Extra legend entries, in black, that explain the markers.
  std::vector<std::pair<std::string, Marker>> markerLegend;
};

/// The data-to-pixel map of a plot: x linear in log10(x) (or x) from the frame's left to right
/// edge, y linear in log10(y) (or y) from the bottom edge (y0) to the top edge (y1).
struct PlotFrame {
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;  ///< data range (log10 already applied on log axes)
  int left = 0, top = 0, right = 0, bottom = 0;
  bool logX = true, logY = false;
  std::pair<int, int> toPixel(double x, double y) const;
};

/// The frame a plot of `series` uses: a log axis spans whole decades around the data, a linear
/// x axis the data, a linear y axis [0, 1.15 max y]; margins leave room for the tick labels,
/// titles and legend column.
PlotFrame plotFrame(const std::vector<PlotSeries>& series, const PlotOptions& options);

/// Draws axes with ticks (decades on a log axis), a dashed line at y = 1 when inside a linear y
/// range, each series as a polyline with its markers, a legend, the title and axis labels.
Canvas linePlot(const std::vector<PlotSeries>& series, const PlotOptions& options);

}  // namespace quadtri
