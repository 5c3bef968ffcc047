#include "quadtri/io/line_plot.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "quadtri/math/error.h"

namespace quadtri {

std::pair<int, int> PlotFrame::toPixel(double x, double y) const {
  const double u = ((logX ? std::log10(x) : x) - x0) / (x1 - x0);
  const double v = ((logY ? std::log10(y) : y) - y0) / (y1 - y0);
  return {int(std::lround(left + u * (right - left))),
          int(std::lround(bottom - v * (bottom - top)))};
}

PlotFrame plotFrame(const std::vector<PlotSeries>& series, const PlotOptions& options) {
  double xMin = INFINITY, xMax = -INFINITY, yMin = INFINITY, yMax = 0;
  for (const PlotSeries& s : series)
    for (const auto& [x, y] : s.points) {
      if (!std::isfinite(x) || !std::isfinite(y) || (options.logX && x <= 0) ||
          (options.logY && y <= 0))
        fail("plot series '{}': point ({}, {}) cannot be drawn", s.label, x, y);
      xMin = std::min(xMin, x);
      xMax = std::max(xMax, x);
      yMin = std::min(yMin, y);
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
  f.logY = options.logY;
  if (options.logY) {
    f.y0 = std::floor(std::log10(yMin));
    f.y1 = std::max(std::ceil(std::log10(yMax)), f.y0 + 1);
  } else {
    f.y0 = 0;
    f.y1 = yMax > 0 ? 1.15 * yMax : 1;
  }
  f.left = 80;
  f.right = options.width - 24 - options.legendWidth;
  f.top = 44;
  f.bottom = options.height - 64;
  return f;
}

namespace {

/// A square of side 2r + 1 centred on (x, y).
void dot(Canvas& c, int x, int y, int r, const Rgb& color) {
  c.fillRect(x - r, y - r, x + r + 1, y + r + 1, color);
}

/// A marker of radius r centred on (x, y); every shape covers its centre pixel.
void marker(Canvas& c, int x, int y, int r, Marker m, const Rgb& color) {
  for (int dy = -r - 1; dy <= r + 1; ++dy)
    for (int dx = -r - 1; dx <= r + 1; ++dx) {
      bool on = false;
      switch (m) {
        case Marker::Square:
          on = std::abs(dx) <= r && std::abs(dy) <= r;
          break;
        case Marker::Circle:  // a ring with a centre dot, so it reads apart from a square
          on = dx * dx + dy * dy == 0 ||
               (dx * dx + dy * dy <= (r + 1) * (r + 1) && dx * dx + dy * dy >= (r - 1) * (r - 1));
          break;
        case Marker::Triangle:  // apex up, base at dy = r
          on = dy >= -r - 1 && dy <= r && 2 * std::abs(dx) <= dy + r + 1;
          break;
        case Marker::Cross:
          on = (std::abs(dx - dy) <= 1 || std::abs(dx + dy) <= 1) && std::abs(dx) <= r + 1;
          break;
      }
      if (on) c.set(x + dx, y + dy, color);
    }
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
  const double xLeft = options.logX ? std::pow(10.0, f.x0) : f.x0;
  if (options.logY) {
    for (int k = int(f.y0); k <= int(f.y1); ++k) {
      const int py = f.toPixel(xLeft, std::pow(10.0, k)).second;
      segment(c, {f.left - 5, py}, {f.left, py}, 0, black);
      c.text(f.left - 30, py + 4, fmt::format("1e{}", k), 12, black, true);
    }
  } else {
    for (int i = 0; i <= 5; ++i) {
      const double y = f.y0 + (f.y1 - f.y0) * i / 5;
      const int py = f.toPixel(xLeft, y).second;
      segment(c, {f.left - 5, py}, {f.left, py}, 0, black);
      c.text(f.left - 30, py + 4, fmt::format("{:.2f}", y), 12, black, true);
    }
  }
  if (!options.logY && f.y1 > 1.0) {
    const double xa = options.logX ? std::pow(10.0, f.x0) : f.x0;
    const double xb = options.logX ? std::pow(10.0, f.x1) : f.x1;
    segment(c, f.toPixel(xa, 1.0), f.toPixel(xb, 1.0), 0, grey, true);
  }
  const int legendX = options.legendWidth > 0 ? f.right + 16 : f.left + 12;
  int legendY = f.top + 8;
  for (const PlotSeries& ps : series) {
    for (size_t i = 0; i + 1 < ps.points.size(); ++i)
      segment(c, f.toPixel(ps.points[i].first, ps.points[i].second),
              f.toPixel(ps.points[i + 1].first, ps.points[i + 1].second), 1, ps.color);
    for (const auto& [x, y] : ps.points) {
      const auto [px, py] = f.toPixel(x, y);
      marker(c, px, py, 3, ps.marker, ps.color);
    }
    if (ps.label.empty()) continue;
    c.fillRect(legendX, legendY - 6, legendX + 20, legendY - 2, ps.color);
    c.text(legendX + 28, legendY, ps.label, 13, black);
    legendY += 20;
  }
  for (const auto& [label, m] : options.markerLegend) {
    marker(c, legendX + 10, legendY - 4, 3, m, black);
    c.text(legendX + 28, legendY, label, 13, black);
    legendY += 20;
  }
  c.text(options.width / 2, 26, options.title, 16, black, true);
  c.text((f.left + f.right) / 2, options.height - 18, options.xLabel, 14, black, true);
  c.text(8, f.top - 10, options.yLabel, 13, black);
  return c;
}

}  // namespace quadtri
