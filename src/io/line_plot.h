// Line plots drawn on a Canvas: the render-time ratios of the thesis' figure 5.5.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "io/canvas.h"

namespace quadtri {

struct PlotSeries {
  std::string label;
  Rgb color;
  std::vector<std::pair<double, double>> points;  ///< (x, y), x > 0 on a log axis
};

struct PlotOptions {
  int width = 720, height = 440;
  std::string title, xLabel, yLabel;
  bool logX = true;
};

/// The data-to-pixel map of a plot: x linear in log10(x) (or x) from the frame's left to right
/// edge, y linear from the bottom edge (y0) to the top edge (y1).
struct PlotFrame {
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;  ///< data range (log10 already applied to x0, x1)
  int left = 0, top = 0, right = 0, bottom = 0;
  bool logX = true;
  std::pair<int, int> toPixel(double x, double y) const;
};

/// The frame a plot of `series` uses: x spans whole decades (log) around the data, y spans
/// [0, 1.15 max y], margins leave room for the tick labels and titles.
PlotFrame plotFrame(const std::vector<PlotSeries>& series, const PlotOptions& options);

/// Draws axes with ticks (decades on a log x axis), a dashed line at y = 1 when inside the
/// range, each series as a polyline with square markers, a legend, the title and axis labels.
Canvas linePlot(const std::vector<PlotSeries>& series, const PlotOptions& options);

}  // namespace quadtri
