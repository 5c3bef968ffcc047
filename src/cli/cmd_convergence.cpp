// `quadtri convergence --shapes A,B --models all -o plot.png --csv samples.csv`: truth_distance
// of every model under refinement, its log–log plot and the observed orders.
#include <fmt/core.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cstring>

#include "commands.h"
#include "normal_flags.h"
#include "quadtri/analysis/convergence.h"
#include "quadtri/io/atomic_file.h"
#include "quadtri/math/error.h"
#include "quadtri/surface/model.h"

namespace quadtri::cli {
namespace {

std::vector<std::string> splitCommas(const std::string& list) {
  std::vector<std::string> out;
  size_t start = 0;
  while (start <= list.size()) {
    const size_t comma = std::min(list.find(',', start), list.size());
    out.push_back(list.substr(start, comma - start));
    start = comma + 1;
  }
  return out;
}

}  // namespace

Action addConvergenceCommand(CLI::App& app) {
  struct Options {
    std::string shapes = "icosphere,ellipsoid:1,0.7,0.5,torus:1,0.35";
    std::string models = "all", plot, csv, ordersCsv;
    NormalFlags normals;
    int levels = 5, fitLevels = 3, truthLevel = 12;
    double floor = 1e-10;
    size_t maxTriangles = 0;
    bool quiet = false;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "convergence", "truth_distance of every model under refinement, and its observed order");
  sub->add_option("--shapes", opt->shapes,
                  "Shapes to refine: icosphere, ellipsoid[:a,b,c], torus[:R,r], uv-sphere, genus2")
      ->capture_default_str();
  sub->add_option("--models", opt->models, "Comma-separated model names, or 'all'")
      ->capture_default_str();
  sub->add_option("--levels", opt->levels, "Refinement levels 0..N of each shape")
      ->capture_default_str();
  sub->add_option("--fit-levels", opt->fitLevels,
                  "The order is the log-log slope over this many finest levels")
      ->capture_default_str();
  sub->add_option("--floor", opt->floor,
                  "Distances below this are round-off (an exact model): not fitted, not drawn")
      ->capture_default_str();
  sub->add_option("--max-triangles", opt->maxTriangles,
                  "Stop refining a shape at the first level with more triangles (0: no limit)")
      ->capture_default_str()
      ->check(wholeNumber());
  sub->add_option("--truth-level", opt->truthLevel, "Sample lattice level per patch")
      ->capture_default_str();
  addNormalFlags(sub, opt->normals,
                 "Vertex normals: file (the shape's analytic ones), average (thesis eq. 2.8) "
                 "or angle (angle-weighted, split at --crease-angle)");
  sub->add_option("-o,--output", opt->plot, "PNG: truth_distance against triangles, log-log")
      ->check(outputFile());
  sub->add_option("--csv", opt->csv, "CSV of every sample")->check(outputFile());
  sub->add_option("--orders-csv", opt->ordersCsv, "CSV of the observed orders")
      ->check(outputFile());
  sub->add_flag("-q,--quiet", opt->quiet, "No progress lines on stderr");
  return [opt]() {
    // A shape's arguments are commas too: a piece that starts like a number continues the
    // shape before it (ellipsoid:1,0.7,0.5).
    std::vector<std::string> shapes;
    for (const std::string& piece : splitCommas(opt->shapes)) {
      if (!shapes.empty() && !piece.empty() && std::strchr("0123456789.-+", piece[0]))
        shapes.back() += "," + piece;
      else
        shapes.push_back(piece);
    }
    for (const std::string& s : shapes)
      if (s.empty()) fail("--shapes '{}': expected comma-separated shapes", opt->shapes);
    std::vector<std::string> models;
    if (opt->models == "all") {
      models = modelNames();
    } else {
      models = splitCommas(opt->models);
      for (const std::string& m : models)
        if (std::find(modelNames().begin(), modelNames().end(), m) == modelNames().end())
          fail("--models: unknown model '{}': expected one of {} or 'all'", m,
               fmt::join(modelNames(), ", "));
    }
    if (!(opt->floor >= 0)) fail("--floor: expected a non-negative number, got {}", opt->floor);
    ConvergenceOptions options;
    options.levels = opt->levels;
    options.truthLevel = opt->truthLevel;
    options.maxTriangles = opt->maxTriangles;
    options.normals = opt->normals.options();
    if (!opt->quiet)
      options.onSample = [](const ConvergenceSample& s) {
        if (s.truthDistance)
          fmt::print(stderr, "{} level {} ({} triangles) {}: {:.3g}\n", s.shape, s.level,
                     s.triangles, s.model, *s.truthDistance);
      };
    options.onError = [](const ConvergenceSample& s, const std::string& error) {
      fmt::print(stderr, "warning: {} level {}, model {}: not measured: {}\n", s.shape, s.level,
                 s.model, error);
    };
    const std::vector<ConvergenceSample> samples = convergenceStudy(shapes, models, options);
    const std::vector<ConvergenceOrder> orders =
        convergenceOrders(samples, opt->fitLevels, opt->floor);
    if (!opt->csv.empty()) writeTextFile(opt->csv, convergenceCsv(samples));
    if (!opt->ordersCsv.empty()) writeTextFile(opt->ordersCsv, ordersCsv(orders));
    if (!opt->plot.empty()) convergencePlot(samples, opt->floor).savePng(opt->plot);
    fmt::print("{}", ordersMarkdown(orders));
    return 0;
  };
}

}  // namespace quadtri::cli
