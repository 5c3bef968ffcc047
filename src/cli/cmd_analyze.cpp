// `quadtri analyze MESH --model NAME|all [--json]`: the DESIGN.md §4 metrics of each model.
#include <fmt/core.h>

#include <chrono>
#include <nlohmann/json.hpp>

#include "analysis/metrics.h"
#include "cli/commands.h"
#include "math/error.h"
#include "mesh/mesh_io.h"

namespace quadtri::cli {

Action addAnalyzeCommand(CLI::App& app) {
  struct Options {
    std::string mesh, model = "all", tessellation = "8", normals = "file";
    bool json = false;
    AnalysisOptions analysis;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "analyze", "Measure how well each model meets the constraints, and its cost");
  sub->add_option("mesh", opt->mesh, "Mesh file or built-in shape spec (e.g. icosphere:3)")
      ->required();
  sub->add_option("--model", opt->model, "Model name, or 'all'")->capture_default_str();
  sub->add_flag("--json", opt->json, "Print one JSON object instead of a table");
  sub->add_option("--lines", opt->analysis.crack.lines, "Random lines for the crack rate")
      ->capture_default_str();
  sub->add_option("--seed", opt->analysis.crack.seed, "Seed of the crack-rate lines")
      ->capture_default_str();
  sub->add_option("--tessellation", opt->tessellation, "Lattice level N, or 'thesis' (50x50 grid)")
      ->capture_default_str();
  sub->add_option("--normals", opt->normals,
                  "Vertex normals: file, average (thesis eq. 2.8) or angle")
      ->check(CLI::IsMember({"file", "average", "angle"}))
      ->capture_default_str();
  return [opt]() {
    opt->analysis.tessellation = Tessellation::parse(opt->tessellation);
    if (opt->analysis.crack.lines == 0) fail("--lines: expected a positive number of lines");
    BuiltinMesh input = loadMeshSpec(opt->mesh, parseNormalSource(opt->normals));
    const auto mesh = std::make_shared<const TriangleMesh>(std::move(input.mesh));
    const std::vector<std::string> names =
        opt->model == "all" ? modelNames() : std::vector<std::string>{opt->model};
    std::vector<ModelMetrics> rows;
    for (const std::string& name : names) {
      const auto start = std::chrono::steady_clock::now();
      const std::unique_ptr<SurfaceModel> model = makeModel(name, mesh);
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      rows.push_back(analyzeModel(*model, opt->mesh, input.truth, seconds, opt->analysis));
    }
    if (!opt->json) {
      fmt::print("mesh: {} ({} triangles)\n{}", opt->mesh, mesh->triangleCount(),
                 metricsTable(rows));
    } else if (opt->model == "all") {
      nlohmann::json models = nlohmann::json::array();
      for (const ModelMetrics& m : rows) models.push_back(toJson(m));
      fmt::print("{}\n", nlohmann::json{{"mesh", opt->mesh}, {"models", models}}.dump(2));
    } else {
      fmt::print("{}\n", toJson(rows.front()).dump(2));
    }
    return 0;
  };
}

}  // namespace quadtri::cli
