// `quadtri analyze MESH --model NAME|all [--json]`: the docs/DESIGN.md §4 metrics of each model.
#include <fmt/core.h>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "normal_flags.h"
#include "quadtri/analysis/heatmaps.h"
#include "quadtri/analysis/metrics.h"
#include "quadtri/analysis/tessellation_view.h"
#include "quadtri/math/error.h"
#include "quadtri/mesh/mesh_io.h"
#include "quadtri/surface/model_memory.h"

namespace quadtri::cli {

Action addAnalyzeCommand(CLI::App& app) {
  struct Options {
    std::string mesh, model = "all", tessellation = "8", heatmaps;
    NormalFlags normals;
    bool json = false, csv = false;
    int heatmapWidth = 1200;
    AnalysisOptions analysis;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "analyze", "Measure how well each model meets the constraints, and its cost");
  sub->add_option("mesh", opt->mesh, "Mesh file or built-in shape spec (e.g. icosphere:3)")
      ->required();
  sub->add_option("--model", opt->model, "Model name, or 'all'")->capture_default_str();
  sub->add_flag("--json", opt->json, "Print one JSON object instead of a table");
  sub->add_flag("--csv", opt->csv, "Print CSV: a header of the JSON keys, one row per model");
  sub->add_option("--lines", opt->analysis.crack.lines, "Random lines for the crack rate")
      ->capture_default_str()
      ->check(positiveWholeNumber());
  sub->add_option("--seed", opt->analysis.crack.seed, "Seed of the crack-rate lines")
      ->capture_default_str()
      ->check(wholeNumber());
  sub->add_option("--tessellation", opt->tessellation,
                  "Lattice level N, 'thesis' (50x50 grid), or 'auto[:TOLERANCE]' (as convert)")
      ->capture_default_str();
  addNormalFlags(sub, opt->normals,
                 "Vertex normals: file (a built-in shape's analytic ones; angle-weighted, split "
                 "at --crease-angle, for a file without normals), average (thesis eq. 2.8) or "
                 "angle (angle-weighted, split at --crease-angle)");
  sub->add_option("--heatmaps", opt->heatmaps,
                  "Folder for PNGs: per-patch heatmaps of the normal as colour and, for implicit "
                  "models, (f_i o f_p)(u,v) and |n_p x n_i| (thesis figs. 5.6, 6.2); and 3D views "
                  "of the corners-only and the 2500-point tessellation, normal as colour, patch "
                  "boundaries in black (figs. 5.3, 5.4)");
  sub->add_option("--heatmap-width", opt->heatmapWidth,
                  "About how many pixels wide the per-patch heatmaps are")
      ->capture_default_str();
  const auto maxMemory = addMaxMemoryOption(*sub);
  return [opt, maxMemory]() {
    if (opt->heatmapWidth < 100 || opt->heatmapWidth > 10000)
      fail("--heatmap-width {}: expected 100 to 10000 pixels", opt->heatmapWidth);
    opt->analysis.tessellation = Tessellation::parse(opt->tessellation);
    const std::vector<std::string> names =
        opt->model == "all" ? modelNames() : std::vector<std::string>{opt->model};
    // The mesh and the dearest of its models (built one at a time, traced for the crack rate;
    // the heatmaps' views tessellate the thesis' grid) must fit in --max-memory.
    MemoryBudget budget;
    budget.maxBytes = maxMemory();
    // `auto` is charged at the highest level it may pick: analyze builds every model in turn
    // and charges the mesh once, before any is built.
    const Tessellation& requested = opt->analysis.tessellation;
    const Tessellation charged = requested.kind == Tessellation::Kind::Adaptive
                                     ? Tessellation{Tessellation::Kind::Lattice, requested.level}
                                     : requested;
    for (const std::string& name : names) {
      setModelBytes(budget, name, charged, ModelUse::Render, /*dearest=*/true);
      if (!opt->heatmaps.empty())
        setModelBytes(budget, name, Tessellation::thesis(), ModelUse::ConvertMesh,
                      /*dearest=*/true);
    }
    BuiltinMesh input = loadMeshSpec(opt->mesh, opt->normals.options(), &budget);
    if (const std::optional<std::string> repaired = repairWarning(input.mesh, opt->mesh))
      fmt::print(stderr, "warning: {}\n", *repaired);
    const auto mesh = std::make_shared<const TriangleMesh>(std::move(input.mesh));
    std::vector<ModelMetrics> rows;
    for (const std::string& name : names) {
      std::function<void(const SurfaceModel&)> heatmaps;
      if (!opt->heatmaps.empty())
        heatmaps = [&](const SurfaceModel& model) {
          for (const auto& path :
               writeHeatmaps(model, opt->heatmaps, input.description, opt->heatmapWidth))
            fmt::print(stderr, "wrote {}\n", path.string());
          for (const auto& path : writeTessellationViews(model, opt->heatmaps))
            fmt::print(stderr, "wrote {}\n", path.string());
        };
      rows.push_back(
          analyzeNamedModel(name, mesh, opt->mesh, input.truth, opt->analysis, heatmaps));
    }
    if (opt->csv) {
      fmt::print("{}", metricsCsv(rows));
    } else if (!opt->json) {
      fmt::print("mesh: {} ({} triangles)\n{}", opt->mesh, mesh->triangleCount(),
                 metricsTable(rows));
    } else if (opt->model == "all") {
      nlohmann::ordered_json models = nlohmann::ordered_json::array();
      for (const ModelMetrics& m : rows) models.push_back(toJson(m));
      fmt::print("{}\n", nlohmann::ordered_json{{"mesh", opt->mesh}, {"models", models}}.dump(2));
    } else {
      fmt::print("{}\n", toJson(rows.front()).dump(2));
    }
    return 0;
  };
}

}  // namespace quadtri::cli
