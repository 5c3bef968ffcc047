#include "quadtri/report/figure.h"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "quadtri/io/line_plot.h"
#include "quadtri/math/error.h"
#include "quadtri/scene/scene_builder.h"

namespace quadtri {

Canvas imageToCanvas(const Image& image) {
  Canvas canvas(image.width, image.height, Rgb{0, 0, 0});
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const Color& c = image.at(x, y);
      // Non-finite channels become black, as writeImage does for files.
      auto display = [](double v) { return std::isfinite(v) ? float(linearToSrgb(v)) : 0.0f; };
      canvas.set(x, y, Rgb{display(c[0]), display(c[1]), display(c[2])});
    }
  return canvas;
}

Canvas composeGrid(const std::vector<std::string>& rowLabels,
                   const std::vector<std::string>& columnLabels, const std::vector<Image>& images,
                   GridLayout* layoutOut) {
  if (rowLabels.empty() || columnLabels.empty()) fail("a grid needs at least one row and column");
  if (images.size() != rowLabels.size() * columnLabels.size())
    fail("grid of {} x {} cells got {} images", rowLabels.size(), columnLabels.size(),
         images.size());
  GridLayout layout;
  layout.rows = int(rowLabels.size());
  layout.columns = int(columnLabels.size());
  layout.cellWidth = images.front().width;
  layout.cellHeight = images.front().height;
  // Labels shrink with small cells and long names so that neighbouring column labels do not
  // overlap (DejaVu Sans averages under 0.6 em per character).
  size_t longest = 1;
  for (const std::string& label : columnLabels) longest = std::max(longest, label.size());
  layout.labelSize = std::clamp(
      std::min(layout.cellWidth / 10, int(double(layout.cellWidth) / (0.6 * double(longest)))), 7,
      16);
  for (size_t i = 0; i < images.size(); ++i)
    if (images[i].width != layout.cellWidth || images[i].height != layout.cellHeight)
      fail("grid cell {} ({}, {}) is {}x{}, expected {}x{} like the first", i,
           rowLabels[i / columnLabels.size()], columnLabels[i % columnLabels.size()],
           images[i].width, images[i].height, layout.cellWidth, layout.cellHeight);

  const Rgb white{1, 1, 1}, black{0, 0, 0};
  Canvas grid(layout.width(), layout.height(), white);
  for (int c = 0; c < layout.columns; ++c)
    grid.text(layout.cellX(c) + layout.cellWidth / 2, layout.headerHeight - 9,
              columnLabels[size_t(c)], layout.labelSize, black, true);
  for (int r = 0; r < layout.rows; ++r) {
    grid.text(6, layout.cellY(r) + layout.cellHeight / 2 + layout.labelSize / 3,
              rowLabels[size_t(r)], layout.labelSize, black);
    for (int c = 0; c < layout.columns; ++c)
      grid.paste(imageToCanvas(images[size_t(r) * size_t(layout.columns) + size_t(c)]),
                 layout.cellX(c), layout.cellY(r));
  }
  if (layoutOut) *layoutOut = layout;
  return grid;
}

std::vector<FigureCell> renderFigureCells(const FigureRequest& request) {
  if (!request.sceneFor) fail("figure: no scene for the shapes");
  if (request.repeats < 1) fail("figure: at least one render per cell, got {}", request.repeats);
  const RenderSettings& settings = request.settings;
  settings.validate();
  if (settings.model)
    fail("figure: the model '{}' is set for every cell; the models are the columns",
         *settings.model);
  using Clock = std::chrono::steady_clock;
  std::vector<FigureCell> cells;
  for (size_t row = 0; row < request.shapes.size(); ++row) {
    if (!request.shard.holds(row)) continue;
    const std::string& shape = request.shapes[row];
    const std::filesystem::path file = request.sceneFor(shape);
    const size_t first = cells.size(), n = request.models.size();
    std::vector<BuiltScene> built;
    for (const std::string& model : request.models) {
      const auto start = Clock::now();
      SceneDefines defines = settings.defines;
      defines["model"] = model;
      defines["shape"] = shape;
      SceneDescription description = loadSceneDescription(file, defines);
      settings.applyTo(description);
      overrideNormals(description, request.normals, request.creaseAngleDeg);
      built.push_back(buildScene(description, model));
      FigureCell cell{shape, model, {}, 0, 0, {}, 0, 0, 0};
      cell.buildSeconds = std::chrono::duration<double>(Clock::now() - start).count();
      cell.primitives = built.back().scene->primitiveCount();
      cell.geometryBytes = built.back().scene->geometryBytes();
      cells.push_back(std::move(cell));
    }
    for (int round = 0; round < request.repeats; ++round)
      for (size_t k = 0; k < n; ++k) {
        const size_t i = (k + size_t(round)) % n;
        RenderOptions options = built[i].options;
        settings.applyTo(options);
        RenderResult result = render(*built[i].scene, *built[i].integrator, options);
        FigureCell& cell = cells[first + i];
        cell.renderTimes.push_back(result.stats.seconds);
        if (round == 0) {
          cell.image = std::move(result.image);
          cell.meanSamplesPerPixel = result.stats.meanSamplesPerPixel();
        }
      }
    for (size_t i = 0; i < n; ++i) {
      FigureCell& cell = cells[first + i];
      cell.renderSeconds = median(cell.renderTimes);
      if (request.onCell) request.onCell(cell);
    }
  }
  return cells;
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const size_t m = values.size() / 2;
  return values.size() % 2 ? values[m] : 0.5 * (values[m - 1] + values[m]);
}

double renderTimeRatio(const FigureCell& num, const FigureCell& den) {
  return renderTimeRatioRange(num, den).median;
}

RatioRange renderTimeRatioRange(const FigureCell& num, const FigureCell& den) {
  if (!num.renderTimes.empty() && num.renderTimes.size() == den.renderTimes.size()) {
    std::vector<double> ratios;
    for (size_t r = 0; r < num.renderTimes.size(); ++r) {
      if (!(den.renderTimes[r] > 0)) return {};
      ratios.push_back(num.renderTimes[r] / den.renderTimes[r]);
    }
    const auto [lo, hi] = std::minmax_element(ratios.begin(), ratios.end());
    return {median(ratios), *lo, *hi};
  }
  const double ratio = den.renderSeconds > 0 ? num.renderSeconds / den.renderSeconds : 0.0;
  return {ratio, ratio, ratio};
}

std::string figureCsv(const std::string& setup, const std::vector<FigureCell>& cells) {
  std::string csv =
      "setup,shape,model,width,height,spp,primitives,geometry_bytes,build_s,render_s,"
      "render_min_s,render_max_s,render_times_s\n";
  for (const FigureCell& c : cells) {
    std::vector<double> times = c.renderTimes;
    if (times.empty()) times.push_back(c.renderSeconds);
    std::string all;
    for (double t : times) all += fmt::format("{}{:.4f}", all.empty() ? "" : ";", t);
    csv += fmt::format("{},{},{},{},{},{:.1f},{},{},{:.4f},{:.4f},{:.4f},{:.4f},{}\n", setup,
                       c.shape, c.model, c.image.width, c.image.height, c.meanSamplesPerPixel,
                       c.primitives, c.geometryBytes, c.buildSeconds, c.renderSeconds,
                       *std::min_element(times.begin(), times.end()),
                       *std::max_element(times.begin(), times.end()), all);
  }
  return csv;
}

std::vector<std::pair<double, double>> renderTimeRatios(const std::vector<FigureCell>& cells,
                                                        const std::string& numerator,
                                                        const std::string& denominator) {
  std::vector<std::pair<double, double>> points;
  for (const FigureCell& num : cells) {
    if (num.model != numerator) continue;
    for (const FigureCell& den : cells)
      if (den.shape == num.shape && den.model == denominator) {
        const double ratio = renderTimeRatio(num, den);
        if (ratio > 0) points.emplace_back(double(num.primitives), ratio);
      }
  }
  std::sort(points.begin(), points.end());
  return points;
}

Canvas renderTimeRatioPlot(const std::vector<FigureCell>& cells,
                           const std::vector<std::string>& models, const std::string& setup) {
  if (models.empty()) fail("a ratio plot needs a model");
  const std::string& numerator = models.back();
  const Rgb colors[] = {
      {0.85f, 0.3f, 0.1f}, {0.1f, 0.4f, 0.8f}, {0.2f, 0.6f, 0.2f}, {0.5f, 0.2f, 0.6f}};
  std::vector<PlotSeries> series;
  for (size_t i = 0; i + 1 < models.size(); ++i)
    series.push_back({fmt::format("{} / {}", numerator, models[i]), colors[i % 4],
                      renderTimeRatios(cells, numerator, models[i])});
  PlotOptions plot;
  plot.title = fmt::format("Render time ratio, setup {}", setup);
  plot.xLabel = fmt::format("{} primitives (patches)", numerator);
  plot.yLabel = "time ratio";
  return linePlot(series, plot);
}

}  // namespace quadtri
