// `quadtri figure --setup a|b -o grid.png [--csv times.csv]`: renders each (shape, model) scene
// of a setup and composes the labelled grid of the thesis' figures 5.1 / 5.2.
#include <fmt/core.h>

#include <algorithm>

#include "commands.h"
#include "normal_flags.h"
#include "quadtri/io/atomic_file.h"
#include "quadtri/math/error.h"
#include "quadtri/report/figure.h"
#include "quadtri/report/figure_cells.h"
#include "render_flags.h"

namespace quadtri::cli {
namespace {}  // namespace

Action addFigureCommand(CLI::App& app) {
  struct Options {
    std::string setup = "a", shapes = "triangle,tetrahedron,icosahedron,teapot",
                models = "shading,quadric-edges,quadric-param,quadric-implicit",
                scenes = "scenes/thesis", output, csv, ratioPlot, shard, cells;
    std::vector<std::string> from;
    int res = 0, repeats = 1;
    RenderFlags flags;
    NormalFlags normals;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "figure",
      "Render each shape with each model and compose a labelled grid (thesis figs. 5.1, 5.2)");
  sub->add_option(
         "--setup", opt->setup,
         "Setup: scene files SCENES/SETUP-SHAPE.xml, or one SCENES/SETUP.xml taking $shape")
      ->capture_default_str();
  sub->add_option("--shapes", opt->shapes, "Comma-separated shapes (grid rows)")
      ->capture_default_str();
  sub->add_option("--models", opt->models, "Comma-separated models (grid columns)")
      ->capture_default_str();
  sub->add_option("--scenes", opt->scenes, "Folder of the scene files")->capture_default_str();
  sub->add_option("-o,--output", opt->output,
                  "Grid image (.png); required unless --shard only renders cells");
  sub->add_option("--csv", opt->csv, "Render time per cell, as CSV");
  sub->add_option("--ratio-plot", opt->ratioPlot,
                  "PNG plot of the render-time ratio of the last model over each other model "
                  "against its primitive count (thesis fig. 5.5)");
  sub->add_option("--res", opt->res, "Image side in pixels (sets $res)");
  opt->flags.add(sub, kSppFlag | kDefineFlag | kThreadsFlag | kSeedFlag | kTimeFlag);
  addNormalFlags(sub, opt->normals,
                 "Shading normals of every obj/ply shape, overriding the scenes': file, average "
                 "(thesis eq. 2.8) or angle (angle-weighted, split at --crease-angle)",
                 "");
  sub->add_option("--shard", opt->shard,
                  "Render only rows I, I+N, ... of N (every model of each, side by side) and "
                  "save their cells in --cells DIR, for --from to compose");
  sub->add_option("--cells", opt->cells,
                  "Folder to save each rendered cell in, as an EXR with its measurements");
  sub->add_option("--from", opt->from,
                  "Compose the figure from the cells saved in these folders (by --shard runs "
                  "with the same options) instead of rendering");
  sub->add_option("--repeat", opt->repeats,
                  "Renders per cell, in rounds that rotate the models' order; the CSV and the "
                  "ratio plot take the median")
      ->capture_default_str();
  return [opt]() {
    FigureRequest request;
    request.shapes = splitList(opt->shapes);
    request.models = splitList(opt->models);
    if (request.shapes.empty() || request.models.empty())
      fail("--shapes and --models need at least one name each");
    for (const std::string& m : request.models) checkModelName("--models", m);
    if (opt->res < 0) fail("--res {}: expected a positive number of pixels", opt->res);
    if (opt->repeats < 1) fail("--repeat {}: expected at least 1", opt->repeats);
    if (!opt->shard.empty()) {
      request.shard = Shard::parse(opt->shard);
      if (opt->cells.empty())
        fail("--shard {}: give --cells DIR to keep the cells for --from", opt->shard);
    }
    if (!opt->from.empty() && (!opt->shard.empty() || !opt->cells.empty()))
      fail("--from composes cells already rendered: it takes no --shard or --cells");
    // A share of the rows cannot make the figure: --from composes it once every shard is done.
    const bool composes = request.shard.count == 1;
    if (!composes && !(opt->output.empty() && opt->csv.empty() && opt->ratioPlot.empty()))
      fail(
          "--shard {}: one shard renders cells only; compose the figure, its CSV and ratio plot "
          "with --from once every shard is done (drop -o, --csv and --ratio-plot here)",
          opt->shard);
    if (composes && opt->output.empty()) fail("-o: the grid image (.png) is required");
    // The outputs' folders must exist before the renders, or be made by --cells (which creates
    // its folder and those above it before the grid is written).
    for (const auto& [flag, file] :
         {std::pair{"-o", &opt->output}, {"--csv", &opt->csv}, {"--ratio-plot", &opt->ratioPlot}}) {
      if (file->empty()) continue;
      const std::filesystem::path path(*file);
      const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : ".";
      if (std::filesystem::is_directory(folder)) continue;
      bool madeByCells = false;
      if (!opt->cells.empty()) {
        const auto f = std::filesystem::absolute(folder).lexically_normal();
        const auto c = std::filesystem::absolute(opt->cells).lexically_normal();
        madeByCells = std::mismatch(f.begin(), f.end(), c.begin(), c.end()).first == f.end();
      }
      if (!madeByCells) fail("{} {}: the folder {} does not exist", flag, *file, folder.string());
    }
    if (!opt->output.empty() && std::filesystem::path(opt->output).extension() != ".png")
      fail("-o {}: expected a .png file", opt->output);
    request.settings = opt->flags.settings();
    if (opt->res > 0) request.settings.defines["res"] = std::to_string(opt->res);
    request.normals = opt->normals.sourceOverride();
    request.creaseAngleDeg = opt->normals.creaseOverride();
    request.repeats = opt->repeats;
    const std::filesystem::path folder = opt->scenes;
    const std::string setup = opt->setup;
    request.sceneFor = [folder, setup](const std::string& shape) {
      const std::filesystem::path perShape = folder / fmt::format("{}-{}.xml", setup, shape);
      const std::filesystem::path shared = folder / fmt::format("{}.xml", setup);
      if (std::filesystem::is_regular_file(perShape)) return perShape;
      if (std::filesystem::is_regular_file(shared)) return shared;
      fail("figure: neither {} nor {} exists (setup '{}', shape '{}')", perShape.string(),
           shared.string(), setup, shape);
    };
    request.onCell = [](const FigureCell& c) {
      const auto [lo, hi] = std::minmax_element(c.renderTimes.begin(), c.renderTimes.end());
      fmt::print(
          "{:<12} {:<18} render {:8.3f} s ({:.3f}-{:.3f}, {} runs)  build {:6.3f} s  {:5.1f} spp  "
          "{} primitives\n",
          c.shape, c.model, c.renderSeconds, *lo, *hi, c.renderTimes.size(), c.buildSeconds,
          c.meanSamplesPerPixel, c.primitives);
      std::fflush(stdout);
    };

    const std::string settingsText = figureSettingsText(request, setup);
    std::vector<FigureCell> cells;
    if (!opt->from.empty()) {
      cells =
          loadFigureCells(request, settingsText,
                          std::vector<std::filesystem::path>(opt->from.begin(), opt->from.end()));
      for (const FigureCell& c : cells) request.onCell(c);
    } else {
      cells = renderFigureCells(request);
      if (!opt->cells.empty()) {
        for (const FigureCell& c : cells)
          saveFigureCell(c, settingsText, opt->cells, request.shard);
        fmt::print("saved {} cells in {}\n", cells.size(), opt->cells);
      }
    }
    if (!composes) return 0;
    std::vector<Image> images;
    for (const FigureCell& c : cells) images.push_back(c.image);
    composeGrid(request.shapes, request.models, images).savePng(opt->output);
    fmt::print("wrote {}\n", opt->output);
    if (!opt->csv.empty()) {
      writeTextFile(opt->csv, figureCsv(setup, cells));
      fmt::print("wrote {}\n", opt->csv);
    }
    if (!opt->ratioPlot.empty()) {
      renderTimeRatioPlot(cells, request.models, setup).savePng(opt->ratioPlot);
      fmt::print("wrote {}\n", opt->ratioPlot);
    }
    return 0;
  };
}

}  // namespace quadtri::cli
