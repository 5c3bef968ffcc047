#include "io/line_plot.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "math/error.h"

namespace quadtri {

std::pair<int, int> PlotFrame::toPixel(double x, double y) const {
  const double u = ((logX ? std::log10(x) : x) - x0) / (x1 - x0);
  const double v = (y - y0) / (y1 - y0);
  return {int(std::lround(left + u * (right - left))),
          int(std::lround(bottom - v * (bottom - top)))};
}

PlotFrame plotFrame(const std::vector<PlotSeries>& series, const PlotOptions& options) {
  double xMin = INFINITY, xMax = -INFINITY, yMax = 0;
  for (const PlotSeries& s : series)
    for (const auto& [x, y] : s.points) {
      if (!std::isfinite(x) || !std::isfinite(y) || (options.logX && x <= 0))
        fail("plot series '{}': point ({}, {}) cannot be drawn", s.label, x, y);
      xMin = std::min(xMin, x);
      xMax = std::max(xMax, x);
      yMax = std::max(yMax, y);
    }
  if (!(xMin <= xMax)) fail("plot '{}' has no points", options.title);
  PlotFrame f;
  f.logX = options.logX;
  if (options.logX) {
    f.x0 = std::floor(std::log10(xMin));
    f.x1 = std::max(std::ceil(std::log10(xMax)), f.x0 + 1);
  } else {
    f.x0 = xMin;
    f.x1 = xMax > xMin ? xMax : xMin + 1;
  }
  f.y0 = 0;
  f.y1 = yMax > 0 ? 1.15 * yMax : 1;
  f.left = 80;
  f.right = options.width - 24;
  f.top = 44;
  f.bottom = options.height - 64;
  return f;
}

namespace {

/// A square of side 2r + 1 centred on (x, y).
void dot(Canvas& c, int x, int y, int r, const Rgb& color) {
  c.fillRect(x - r, y - r, x + r + 1, y + r + 1, color);
}

/// Samples the segment densely enough that consecutive dots touch (width 2r + 1).
void segment(Canvas& c, std::pair<int, int> a, std::pair<int, int> b, int r, const Rgb& color,
             bool dashed = false) {
  const int steps = std::max({std::abs(b.first - a.first), std::abs(b.second - a.second), 1});
  for (int i = 0; i <= steps; ++i) {
    if (dashed && (i / 6) % 2 == 1) continue;
    const double t = double(i) / steps;
    dot(c, int(std::lround(a.first + t * (b.first - a.first))),
        int(std::lround(a.second + t * (b.second - a.second))), r, color);
  }
}

}  // namespace

Canvas linePlot(const std::vector<PlotSeries>& series, const PlotOptions& options) {
  const PlotFrame f = plotFrame(series, options);
  const Rgb white{1, 1, 1}, black{0, 0, 0}, grey{0.6f, 0.6f, 0.6f};
  Canvas c(options.width, options.height, white);
  segment(c, {f.left, f.bottom}, {f.right, f.bottom}, 0, black);
  segment(c, {f.left, f.bottom}, {f.left, f.top}, 0, black);
  if (options.logX) {
    for (int k = int(f.x0); k <= int(f.x1); ++k) {
      const int x = f.toPixel(std::pow(10.0, k), 0).first;
      segment(c, {x, f.bottom}, {x, f.bottom + 5}, 0, black);
      c.text(x, f.bottom + 20,
             k <= 6 ? fmt::format("{:.0f}", std::pow(10.0, k)) : fmt::format("1e{}", k), 12, black,
             true);
    }
  }
  for (int i = 0; i <= 5; ++i) {
    const double y = f.y0 + (f.y1 - f.y0) * i / 5;
    const int py = f.toPixel(options.logX ? std::pow(10.0, f.x0) : f.x0, y).second;
    segment(c, {f.left - 5, py}, {f.left, py}, 0, black);
    c.text(f.left - 30, py + 4, fmt::format("{:.2f}", y), 12, black, true);
  }
  if (f.y1 > 1.0) {
    const double xa = options.logX ? std::pow(10.0, f.x0) : f.x0;
    const double xb = options.logX ? std::pow(10.0, f.x1) : f.x1;
    segment(c, f.toPixel(xa, 1.0), f.toPixel(xb, 1.0), 0, grey, true);
  }
  for (size_t s = 0; s < series.size(); ++s) {
    const PlotSeries& ps = series[s];
    for (size_t i = 0; i + 1 < ps.points.size(); ++i)
      segment(c, f.toPixel(ps.points[i].first, ps.points[i].second),
              f.toPixel(ps.points[i + 1].first, ps.points[i + 1].second), 1, ps.color);
    for (const auto& [x, y] : ps.points) {
      const auto [px, py] = f.toPixel(x, y);
      dot(c, px, py, 3, ps.color);
    }
    const int ly = f.top + 8 + int(s) * 20;
    c.fillRect(f.left + 12, ly - 6, f.left + 32, ly - 2, ps.color);
    c.text(f.left + 40, ly, ps.label, 13, black);
  }
  c.text(options.width / 2, 26, options.title, 16, black, true);
  c.text((f.left + f.right) / 2, options.height - 18, options.xLabel, 14, black, true);
  c.text(8, f.top - 10, options.yLabel, 13, black);
  return c;
}

}  // namespace quadtri
