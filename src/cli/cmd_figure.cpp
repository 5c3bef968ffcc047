// `quadtri figure --setup a|b -o grid.png [--csv times.csv]`: renders each (shape, model) scene
// of a setup and composes the labelled grid of the thesis' figures 5.1 / 5.2.
#include <fmt/core.h>

#include <algorithm>
#include <sstream>

#include "commands.h"
#include "normal_flags.h"
#include "quadtri/io/atomic_file.h"
#include "quadtri/math/error.h"
#include "quadtri/report/figure.h"
#include "quadtri/surface/model.h"

namespace quadtri::cli {
namespace {

std::vector<std::string> splitList(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) items.push_back(item);
  return items;
}

}  // namespace

Action addFigureCommand(CLI::App& app) {
  struct Options {
    std::string setup = "a", shapes = "triangle,tetrahedron,icosahedron,teapot",
                models = "shading,quadric-edges,quadric-param,quadric-implicit",
                scenes = "scenes/thesis", output, csv, ratioPlot;
    std::vector<std::string> defines;
    int spp = 0, res = 0, threads = 0, repeats = 1;
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
  sub->add_option("-o,--output", opt->output, "Grid image (.png)")->required();
  sub->add_option("--csv", opt->csv, "Render time per cell, as CSV");
  sub->add_option("--ratio-plot", opt->ratioPlot,
                  "PNG plot of the render-time ratio of the last model over each other model "
                  "against its primitive count (thesis fig. 5.5)");
  sub->add_option("--spp", opt->spp, "Samples per pixel (sets $spp and overrides the sampler)");
  sub->add_option("--res", opt->res, "Image side in pixels (sets $res)");
  sub->add_option("-D", opt->defines, "Scene parameter name=value (overrides <default>)");
  sub->add_option("--threads", opt->threads, "Worker threads (0: all)")->capture_default_str();
  addNormalFlags(sub, opt->normals,
                 "Shading normals of every obj/ply shape, overriding the scenes': file, average "
                 "(thesis eq. 2.8) or angle (angle-weighted, split at --crease-angle)",
                 "");
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
    const std::vector<std::string>& known = modelNames();
    for (const std::string& m : request.models)
      if (std::find(known.begin(), known.end(), m) == known.end())
        fail("--models: '{}' is not a model", m);
    if (opt->spp < 0 || opt->res < 0 || opt->threads < 0)
      fail("--spp, --res and --threads expect positive numbers");
    if (opt->repeats < 1) fail("--repeat {}: expected at least 1", opt->repeats);
    if (std::filesystem::path(opt->output).extension() != ".png")
      fail("-o {}: expected a .png file", opt->output);
    for (const std::string& d : opt->defines) {
      const size_t eq = d.find('=');
      if (eq == std::string::npos || eq == 0) fail("-D {}: expected name=value", d);
      request.defines[d.substr(0, eq)] = d.substr(eq + 1);
    }
    if (opt->spp > 0) {
      request.defines["spp"] = std::to_string(opt->spp);
      request.samplesPerPixel = opt->spp;
    }
    if (opt->res > 0) request.defines["res"] = std::to_string(opt->res);
    request.threads = opt->threads;
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

    const std::vector<FigureCell> cells = renderFigureCells(request);
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
