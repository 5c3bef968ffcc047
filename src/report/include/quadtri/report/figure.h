// Labelled grids of renders, like the thesis' figures 5.1 and 5.2: rows = shapes, columns =
// models, each cell one scene rendered with one model, and the render times behind tables
// 5.2 and 5.3.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "quadtri/io/canvas.h"
#include "quadtri/render/image_io.h"
#include "quadtri/report/shard.h"
#include "quadtri/scene/render_settings.h"
#include "quadtri/scene/scene_loader.h"

namespace quadtri {

/// Converts a linear image to display values with the sRGB curve (clamped to [0, 1]).
Canvas imageToCanvas(const Image& image);

/// Where the cells and labels of a grid go; every cell has the same size.
struct GridLayout {
  int rows = 0, columns = 0;
  int cellWidth = 0, cellHeight = 0;
  int rowLabelWidth = 130;  ///< band on the left holding the row labels
  int headerHeight = 30;    ///< band on top holding the column labels
  int gap = 4;              ///< space around and between cells
  int labelSize = 16;  ///< text size in pixels (composeGrid: fits the longest column label, 7-16)

  int width() const { return rowLabelWidth + columns * cellWidth + (columns + 1) * gap; }
  int height() const { return headerHeight + rows * cellHeight + (rows + 1) * gap; }
  /// Top-left pixel of cell (row, column): x = L + g + c(w + g), y = T + g + r(h + g).
  int cellX(int column) const { return rowLabelWidth + gap + column * (cellWidth + gap); }
  int cellY(int row) const { return headerHeight + gap + row * (cellHeight + gap); }
};

/// Composes `images` (row-major, rows × columns, all the same size) into a white grid with
/// the column labels centred above each column and the row labels left of each row. Throws
/// Error when the counts or sizes disagree.
Canvas composeGrid(const std::vector<std::string>& rowLabels,
                   const std::vector<std::string>& columnLabels, const std::vector<Image>& images,
                   GridLayout* layoutOut = nullptr);

/// One rendered cell and what it cost.
struct FigureCell {
  std::string shape, model;
  Image image;
  double buildSeconds = 0;   ///< loading, model conversion and acceleration structure
  double renderSeconds = 0;  ///< the renderer's wall time: the median of renderTimes
  /// The wall time of every render of this cell, in round order (FigureRequest::repeats).
  std::vector<double> renderTimes;
  double meanSamplesPerPixel = 0;
  size_t primitives = 0;  ///< of the whole scene (room included)
  size_t geometryBytes = 0;
};

/// What to render: each shape's scene file, rendered once per model (the scene's obj/ply shapes
/// take the model), with the settings' defines for the scene's $parameters.
struct FigureRequest {
  std::vector<std::string> shapes, models;
  std::function<std::filesystem::path(const std::string& shape)> sceneFor;
  /// -D, --spp, --seed, --threads, --time with the meaning they have in `quadtri render`
  /// (RenderSettings); `model` must be unset: each column sets its own.
  RenderSettings settings;
  /// Override every obj/ply shape's normals and crease angle when set (overrideNormals).
  std::optional<NormalSource> normals;
  std::optional<double> creaseAngleDeg;
  /// Renders per cell. A shape's models are built together and rendered in rounds, each round
  /// rendering every model once in an order rotated by one per round, so that a drift of the
  /// machine's load hits every model alike.
  int repeats = 1;
  /// Called after each cell, e.g. to report progress.
  std::function<void(const FigureCell&)> onCell;
  /// Render only the rows (shapes) of this share, every model of each (figure_cells.h).
  Shard shard;
};

/// Renders every (shape, model) cell of the shard's rows, row-major (shapes outer). The defines
/// `model` and `shape` are set to the cell's model and shape, so one scene may serve every shape.
/// Throws Error for settings RenderSettings::validate refuses or that name a model. The image of a
/// cell is that of its first render.
std::vector<FigureCell> renderFigureCells(const FigureRequest& request);

/// The median of `values` (the mean of the middle two for an even count); 0 when empty.
double median(std::vector<double> values);

/// The render-time ratio num / den of two cells rendered side by side: the median over rounds
/// of num.renderTimes[r] / den.renderTimes[r] when both have the same rounds, else
/// num.renderSeconds / den.renderSeconds. 0 when a denominator time is not positive.
double renderTimeRatio(const FigureCell& num, const FigureCell& den);

/// renderTimeRatio with the range of the per-round ratios it takes the median of (lo = hi =
/// median when the cells have no common rounds; all 0 when a denominator is not positive).
struct RatioRange {
  double median = 0, lo = 0, hi = 0;
};
RatioRange renderTimeRatioRange(const FigureCell& num, const FigureCell& den);

/// CSV of the cells' costs: setup,shape,model,width,height,spp,primitives,geometry_bytes,
/// build_s,render_s,render_min_s,render_max_s,render_times_s (render_s the median; the last
/// column lists every round's time, separated by ';').
std::string figureCsv(const std::string& setup, const std::vector<FigureCell>& cells);

/// The thesis' figure 5.5 extended: the points (patches, renderTimeRatio(numerator,
/// denominator)) over the shapes, sorted by patches, where patches is the
/// numerator cell's primitive count (the scaling scene holds nothing else). Shapes missing
/// either cell are skipped.
std::vector<std::pair<double, double>> renderTimeRatios(const std::vector<FigureCell>& cells,
                                                        const std::string& numerator,
                                                        const std::string& denominator);

/// The plot of figure 5.5 extended: renderTimeRatios of the last of `models` over each other
/// one against the last model's primitives, titled with `setup`.
Canvas renderTimeRatioPlot(const std::vector<FigureCell>& cells,
                           const std::vector<std::string>& models, const std::string& setup);

}  // namespace quadtri
