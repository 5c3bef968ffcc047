// `quadtri convert MESH --model NAME -o OUT`: converts a mesh with one model and writes the
// tessellated surface (OBJ, PLY) or the patches themselves (JSON).
#include <fmt/core.h>

#include <chrono>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "io/atomic_file.h"
#include "math/error.h"
#include "mesh/mesh_io.h"
#include "surface/model.h"
#include "surface/tessellate.h"

namespace quadtri::cli {
namespace {

std::string tessellationText(const Tessellation& t) {
  return t.kind == Tessellation::Kind::ThesisGrid ? "thesis" : std::to_string(t.level);
}

}  // namespace

Action addConvertCommand(CLI::App& app) {
  struct Options {
    std::string mesh, model, output, tessellation = "8", normals = "file";
  };
  auto opt = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "convert",
      "Convert a mesh with one model. OBJ/PLY output: the model's surface tessellated (a "
      "triangle lattice of level N per patch, N² triangles; default 8), or the input triangles "
      "for flat/shading. JSON output: {\"model\", \"triangles\", \"tessellation\", \"patches\"} "
      "with each patch's data.");
  sub->add_option("mesh", opt->mesh, "Mesh file (OBJ, PLY, ...) or built-in shape (icosphere:3)")
      ->required();
  sub->add_option("--model", opt->model, "Model")->required()->check(CLI::IsMember(modelNames()));
  sub->add_option("-o,--output", opt->output, "Output file: .obj, .ply (tessellated) or .json")
      ->required();
  sub->add_option("--tessellation", opt->tessellation,
                  "Lattice level N (N² triangles per patch) or 'thesis' (50x50 grid, 4802 "
                  "triangles per patch)")
      ->capture_default_str();
  sub->add_option("--normals", opt->normals,
                  "Shading normals: file (as given; computed by average when missing), average "
                  "(thesis eq. 2.8) or angle (angle-weighted)")
      ->check(CLI::IsMember({"file", "average", "angle"}))
      ->capture_default_str();
  return [opt]() {
    const Tessellation tessellation = Tessellation::parse(opt->tessellation);
    const std::filesystem::path output = opt->output;
    const std::string ext = output.extension().string();
    if (ext != ".obj" && ext != ".ply" && ext != ".json")
      fail("{}: unknown output extension '{}': expected .obj, .ply or .json", opt->output, ext);
    BuiltinMesh input = loadMeshSpec(opt->mesh, parseNormalSource(opt->normals));
    input.mesh.validate(opt->mesh);
    auto mesh = std::make_shared<const TriangleMesh>(std::move(input.mesh));
    const auto start = std::chrono::steady_clock::now();
    const std::unique_ptr<SurfaceModel> model = makeModel(opt->model, mesh);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (ext == ".json") {
      nlohmann::json j;
      j["model"] = opt->model;
      j["triangles"] = mesh->triangleCount();
      j["tessellation"] = tessellationText(tessellation);
      j["patches"] = nlohmann::json::array();
      for (size_t t = 0; t < model->patchCount(); ++t) j["patches"].push_back(model->patchJson(t));
      writeTextFile(output, j.dump() + "\n");
      fmt::print("{}: {} model of {} ({} triangles, {} patches, converted in {:.3f} s)\n",
                 opt->output, opt->model, input.description, mesh->triangleCount(),
                 model->patchCount(), seconds);
    } else {
      const TriangleMesh out = tessellate(*model, tessellation);
      saveMesh(out, output);
      fmt::print(
          "{}: {} model of {} ({} triangles -> {} vertices, {} triangles, tessellation {}, "
          "converted in {:.3f} s)\n",
          opt->output, opt->model, input.description, mesh->triangleCount(), out.positions.size(),
          out.triangleCount(), tessellationText(tessellation), seconds);
    }
    return 0;
  };
}

}  // namespace quadtri::cli
