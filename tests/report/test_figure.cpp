// Figure grids: the layout's size, each cell's pixels from its own render, labels drawn.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>

#include "quadtri/math/error.h"
#include "quadtri/report/figure.h"
#include "quadtri/report/figure_cells.h"

namespace quadtri::testing {
namespace {

Image constantImage(int w, int h, double value) {
  Image image(w, h);
  for (Color& c : image.pixels) c = Color::Constant(value);
  return image;
}

/// Mean of channel 0 over a rectangle of the canvas.
double meanRed(const Canvas& canvas, int x0, int y0, int w, int h) {
  double sum = 0;
  for (int y = y0; y < y0 + h; ++y)
    for (int x = x0; x < x0 + w; ++x) sum += canvas.get(x, y)[0];
  return sum / double(w * h);
}

/// Pixels of a rectangle darker than mid grey: label ink on the white background.
int inkPixels(const Canvas& canvas, int x0, int y0, int x1, int y1) {
  int count = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) count += canvas.get(x, y)[0] < 0.5f ? 1 : 0;
  return count;
}

TEST(FigureGrid, CellsHoldTheirImagesAndLabelsAreDrawn) {
  const std::vector<std::string> rows = {"triangle", "icosahedron"};
  const std::vector<std::string> columns = {"shading", "quadric-param", "quadric-implicit"};
  std::vector<Image> images;
  for (size_t i = 0; i < 6; ++i) images.push_back(constantImage(40, 30, 0.05 + 0.15 * double(i)));
  GridLayout layout;
  const Canvas grid = composeGrid(rows, columns, images, &layout);
  EXPECT_EQ(grid.width(), layout.rowLabelWidth + 3 * 40 + 4 * layout.gap);
  EXPECT_EQ(grid.height(), layout.headerHeight + 2 * 30 + 3 * layout.gap);
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 3; ++c) {
      const double expected = linearToSrgb(0.05 + 0.15 * double(r * 3 + c));
      EXPECT_NEAR(meanRed(grid, layout.cellX(c), layout.cellY(r), 40, 30), expected, 1e-6)
          << rows[size_t(r)] << " / " << columns[size_t(c)];
      // The gap just left of the cell is background, so the cell is not shifted.
      EXPECT_EQ(grid.get(layout.cellX(c) - 1, layout.cellY(r))[0], 1.0f);
    }
  for (int c = 0; c < 3; ++c)
    EXPECT_GT(inkPixels(grid, layout.cellX(c), 0, layout.cellX(c) + 40, layout.headerHeight), 10)
        << "column label " << columns[size_t(c)];
  for (int r = 0; r < 2; ++r)
    EXPECT_GT(inkPixels(grid, 0, layout.cellY(r), layout.rowLabelWidth, layout.cellY(r) + 30), 10)
        << "row label " << rows[size_t(r)];
  // Between the labels the bands stay background.
  EXPECT_EQ(inkPixels(grid, 0, 0, layout.rowLabelWidth, layout.headerHeight), 0);
}

TEST(FigureGrid, RejectsMismatchedCells) {
  std::vector<Image> images = {constantImage(8, 8, 0.5), constantImage(8, 9, 0.5)};
  EXPECT_THROW(composeGrid({"a"}, {"x", "y"}, images), Error);
  images.pop_back();
  EXPECT_THROW(composeGrid({"a"}, {"x", "y"}, images), Error);
}

TEST(FigureGrid, ImageToCanvasAppliesTheSrgbCurveAndDropsNonFinite) {
  Image image = constantImage(2, 1, 0.2);
  image.at(1, 0) = Color(std::nan(""), 2.0, -1.0);
  const Canvas canvas = imageToCanvas(image);
  EXPECT_NEAR(canvas.get(0, 0)[1], linearToSrgb(0.2), 1e-6);
  EXPECT_EQ(canvas.get(1, 0)[0], 0.0f);
  EXPECT_EQ(canvas.get(1, 0)[1], 1.0f);
  EXPECT_EQ(canvas.get(1, 0)[2], 0.0f);
}

/// Writes a scene that sees only a constant environment of the given radiance.
void writeSkyScene(const std::filesystem::path& file, double radiance) {
  std::ofstream out(file);
  out << "<scene version=\"3.0.0\">\n"
         "  <default name=\"res\" value=\"32\"/> <default name=\"spp\" value=\"64\"/>\n"
         "  <integrator type=\"path\"/>\n"
         "  <sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/>\n"
         "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"$res\"/>"
         "<integer name=\"height\" value=\"$res\"/></film>\n"
         "    <sampler type=\"independent\"><integer name=\"sample_count\" value=\"$spp\"/>"
         "</sampler>\n"
         "  </sensor>\n"
      << "  <emitter type=\"constant\"><rgb name=\"radiance\" value=\"" << radiance
      << "\"/></emitter>\n</scene>\n";
}

TEST(FigureCells, EachCellComesFromItsShapesSceneWithTheDefines) {
  const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / ("quadtri_figure_" + std::to_string(::getpid()));
  std::filesystem::create_directories(folder);
  writeSkyScene(folder / "t-dim.xml", 0.2);
  writeSkyScene(folder / "t-bright.xml", 0.7);
  FigureRequest request;
  request.shapes = {"dim", "bright"};
  request.models = {"shading", "quadric-implicit"};
  request.sceneFor = [&](const std::string& shape) { return folder / ("t-" + shape + ".xml"); };
  request.settings.defines["res"] = "6";
  request.settings.samplesPerPixel = 2;
  int calls = 0;
  request.onCell = [&](const FigureCell&) { ++calls; };
  const std::vector<FigureCell> cells = renderFigureCells(request);
  std::filesystem::remove_all(folder);

  ASSERT_EQ(cells.size(), 4u);
  EXPECT_EQ(calls, 4);
  const double expected[] = {0.2, 0.2, 0.7, 0.7};
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(cells[i].shape, request.shapes[i / 2]);
    EXPECT_EQ(cells[i].model, request.models[i % 2]);
    ASSERT_EQ(cells[i].image.width, 6);  // $res from the defines
    EXPECT_NEAR(cells[i].meanSamplesPerPixel, 2.0, 1e-12);
    // A camera ray that escapes sees exactly the constant radiance, whatever the sample.
    for (const Color& c : cells[i].image.pixels) EXPECT_NEAR(c[0], expected[i], 1e-9);
    EXPECT_GE(cells[i].renderSeconds, 0.0);
  }
  for (const FigureCell& c : cells) EXPECT_EQ(c.renderTimes.size(), 1u);
  const std::string csv = figureCsv("t", cells);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 5);
  EXPECT_NE(csv.find("t,bright,quadric-implicit,6,6,2.0,"), std::string::npos);
}

TEST(FigureCells, RepeatsRenderEveryCellOncePerRoundAndKeepTheMedian) {
  const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / ("quadtri_repeat_" + std::to_string(::getpid()));
  std::filesystem::create_directories(folder);
  writeSkyScene(folder / "t-sky.xml", 0.5);
  FigureRequest request;
  request.shapes = {"sky"};
  request.models = {"shading", "quadric-param", "quadric-implicit"};
  request.sceneFor = [&](const std::string& shape) { return folder / ("t-" + shape + ".xml"); };
  request.settings.defines["res"] = "4";
  request.settings.samplesPerPixel = 1;
  request.repeats = 4;
  const std::vector<FigureCell> cells = renderFigureCells(request);
  std::filesystem::remove_all(folder);
  ASSERT_EQ(cells.size(), 3u);
  for (const FigureCell& c : cells) {
    ASSERT_EQ(c.renderTimes.size(), 4u);
    EXPECT_DOUBLE_EQ(c.renderSeconds, median(c.renderTimes));
    EXPECT_EQ(c.image.width, 4);
  }
  const std::string csv = figureCsv("t", cells);
  // render_times_s lists the four rounds, separated by ';'.
  EXPECT_EQ(std::count(csv.begin(), csv.end(), ';'), 3 * 3);
  request.repeats = 0;
  EXPECT_THROW(renderFigureCells(request), Error);
}

TEST(FigureCells, MedianAndSideBySideRatios) {
  EXPECT_DOUBLE_EQ(median({3.0, 1.0, 2.0}), 2.0);
  EXPECT_DOUBLE_EQ(median({4.0, 1.0, 2.0, 3.0}), 2.5);
  EXPECT_DOUBLE_EQ(median({}), 0.0);
  FigureCell num, den;
  // Round 2 ran under load for both: its ratio stays 2, and the median of the per-round
  // ratios (2, 2, 4) is 2 although the median times alone would give 4 / 1.
  num.renderTimes = {2.0, 8.0, 4.0};
  den.renderTimes = {1.0, 4.0, 1.0};
  num.renderSeconds = 4.0;
  den.renderSeconds = 1.0;
  EXPECT_DOUBLE_EQ(renderTimeRatio(num, den), 2.0);
  den.renderTimes = {1.0};  // rounds differ: the ratio of the medians
  EXPECT_DOUBLE_EQ(renderTimeRatio(num, den), 4.0);
}

TEST(FigureCells, RenderTimeRatiosPairCellsOfTheSameShape) {
  auto cell = [](const std::string& shape, const std::string& model, size_t primitives,
                 double seconds) {
    FigureCell c;
    c.shape = shape;
    c.model = model;
    c.primitives = primitives;
    c.renderSeconds = seconds;
    return c;
  };
  const std::vector<FigureCell> cells = {
      cell("big", "quadric-implicit", 320, 3.0), cell("big", "shading", 999, 2.0),
      cell("small", "quadric-implicit", 20, 1.0), cell("small", "shading", 888, 4.0),
      cell("lonely", "quadric-implicit", 5, 1.0)};
  const auto points = renderTimeRatios(cells, "quadric-implicit", "shading");
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[0], std::make_pair(20.0, 0.25));
  EXPECT_EQ(points[1], std::make_pair(320.0, 1.5));
}

/// A diffuse sphere under a constant sky: its pixels depend on the sampler's seed.
void writeSphereScene(const std::filesystem::path& file, double radiance) {
  std::ofstream out(file);
  out << "<scene version=\"3.0.0\">\n"
         "  <default name=\"res\" value=\"8\"/>\n"
         "  <integrator type=\"path\"><integer name=\"max_depth\" value=\"3\"/></integrator>\n"
         "  <sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/>\n"
         "    <transform name=\"to_world\"><lookat origin=\"0, 0, 4\" target=\"0, 0, 0\" "
         "up=\"0, 1, 0\"/></transform>\n"
         "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"$res\"/>"
         "<integer name=\"height\" value=\"$res\"/></film>\n"
         "    <sampler type=\"independent\"><integer name=\"sample_count\" value=\"2\"/>"
         "</sampler>\n"
         "  </sensor>\n"
      << "  <emitter type=\"constant\"><rgb name=\"radiance\" value=\"" << radiance
      << "\"/></emitter>\n  <shape type=\"sphere\"><bsdf type=\"diffuse\"/></shape>\n</scene>\n";
}

TEST(FigureCells, ShardsSavedAndComposedAreTheOneShotFigure) {
  const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / ("quadtri_shards_" + std::to_string(::getpid()));
  std::filesystem::create_directories(folder);
  for (const char* shape : {"a", "b", "c"})
    writeSphereScene(folder / (std::string("t-") + shape + ".xml"), shape[0] == 'b' ? 0.5 : 1.0);
  FigureRequest request;
  request.shapes = {"a", "b", "c"};
  request.models = {"shading", "quadric-implicit"};
  request.sceneFor = [&](const std::string& shape) { return folder / ("t-" + shape + ".xml"); };
  request.settings.seed = 7;
  request.repeats = 2;
  const std::string text = figureSettingsText(request, "t");
  const std::vector<FigureCell> oneShot = renderFigureCells(request);

  // Shard I of 2 renders rows I-1, I+1, ...: every model of each, and saves them.
  std::vector<std::vector<FigureCell>> shards;
  for (size_t i = 1; i <= 2; ++i) {
    FigureRequest part = request;
    part.shard = Shard{i, 2};
    shards.push_back(renderFigureCells(part));
    for (const FigureCell& c : shards.back())
      saveFigureCell(c, text, folder / ("cells-" + std::to_string(i)), part.shard);
  }
  ASSERT_EQ(shards[0].size(), 4u);  // rows a and c
  ASSERT_EQ(shards[1].size(), 2u);  // row b
  EXPECT_EQ(shards[1][0].shape, "b");

  const std::vector<FigureCell> composed =
      loadFigureCells(request, text, {folder / "cells-1", folder / "cells-2"}, 2);
  ASSERT_EQ(composed.size(), oneShot.size());
  for (size_t i = 0; i < composed.size(); ++i) {
    EXPECT_EQ(composed[i].shape, oneShot[i].shape);
    EXPECT_EQ(composed[i].model, oneShot[i].model);
    ASSERT_EQ(composed[i].image.pixels.size(), oneShot[i].image.pixels.size());
    // Per-pixel random streams: the shard's pixels are the one-shot's (floats in the EXR).
    for (size_t p = 0; p < composed[i].image.pixels.size(); ++p)
      for (int c = 0; c < 3; ++c)
        EXPECT_EQ(composed[i].image.pixels[p][c], double(float(oneShot[i].image.pixels[p][c])));
    EXPECT_EQ(composed[i].primitives, oneShot[i].primitives);
    EXPECT_EQ(composed[i].renderTimes.size(), 2u);
  }
  // The measurements come back exactly as the shard measured them.
  const FigureCell& b = composed[2];
  EXPECT_EQ(b.renderTimes, shards[1][0].renderTimes);
  EXPECT_EQ(b.buildSeconds, shards[1][0].buildSeconds);
  EXPECT_EQ(b.renderSeconds, median(shards[1][0].renderTimes));

  // A missing shard names its cells and the shard that renders them.
  try {
    loadFigureCells(request, text, {folder / "cells-1"});  // the cells say "of 2"
    ADD_FAILURE() << "a missing shard was not noticed";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("b / shading (rendered by --shard 2/2)"), std::string::npos) << what;
    EXPECT_NE(what.find("b / quadric-implicit (rendered by --shard 2/2)"), std::string::npos)
        << what;
  }
  // Cells of other settings, or a cell given twice, are refused by file.
  FigureRequest other = request;
  other.settings.seed = 8;
  try {
    loadFigureCells(other, figureSettingsText(other, "t"), {folder / "cells-1"});
    ADD_FAILURE() << "cells of another seed were accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("a cell of another figure: seed=7 against seed=8"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(loadFigureCells(request, text, {folder / "cells-1", folder / "cells-1"}), Error);
  std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace quadtri::testing
