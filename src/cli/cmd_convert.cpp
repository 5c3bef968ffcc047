// `quadtri convert MESH --model NAME -o OUT`: converts a mesh with one model and writes the
// tessellated surface (OBJ, PLY) or the patches themselves (JSON, or the binary patch table).
#include <fmt/core.h>

#include <chrono>

#include "commands.h"
#include "normal_flags.h"
#include "quadtri/mesh/mesh_io.h"
#include "quadtri/surface/convert_output.h"
#include "quadtri/surface/corner_stats.h"
#include "quadtri/surface/model_memory.h"

namespace quadtri::cli {

Action addConvertCommand(CLI::App& app) {
  struct Options {
    std::string mesh, model, output, tessellation = "8";
    NormalFlags normals;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "convert",
      "Convert a mesh with one model. OBJ/PLY output: the model's surface tessellated (a "
      "triangle lattice of level N per patch, N² triangles; default 8), or the input triangles "
      "for flat, shading and shading-offset. JSON output: {\"model\", \"triangles\", "
      "\"tessellation\", \"patches\"} "
      "with each patch's data. QTP output: the same data as a binary table of fixed-size "
      "records (README, \"Binary patch table\").");
  sub->add_option("mesh", opt->mesh, "Mesh file (OBJ, PLY, ...) or built-in shape (icosphere:3)")
      ->required();
  sub->add_option("--model", opt->model, "Model")->required()->check(CLI::IsMember(modelNames()));
  sub->add_option("-o,--output", opt->output,
                  "Output file: .obj, .ply (tessellated), .json or .qtp (patches)")
      ->required()
      ->check(outputFile());
  sub->add_option("--tessellation", opt->tessellation,
                  "Lattice level N (N² triangles per patch), 'thesis' (50x50 grid, 4802 "
                  "triangles per patch), or 'auto[:TOLERANCE]': the lowest level up to 8 whose "
                  "triangles stay within TOLERANCE (default 1e-4) of the bounding-box diagonal "
                  "from the surface")
      ->capture_default_str();
  addNormalFlags(sub, opt->normals,
                 "Shading normals: file (as given; angle-weighted and split at --crease-angle "
                 "when missing), average (thesis eq. 2.8) or angle (angle-weighted, split at "
                 "--crease-angle)");
  const auto maxMemory = addMaxMemoryOption(*sub);
  return [opt, maxMemory]() {
    const Tessellation requested = Tessellation::parse(opt->tessellation);
    // The mesh and its model must fit in --max-memory, checked before either is built.
    MemoryBudget budget;
    budget.maxBytes = maxMemory();
    const std::string extension = conversionExtension(opt->output);
    const bool writesPatches = extension == ".json" || extension == ".qtp";
    // An OBJ/PLY surface is charged as it is written: streamed (saveTessellation).
    const ModelUse use = writesPatches ? ModelUse::ConvertJson : ModelUse::ConvertMeshStreamed;
    setModelBytes(budget, opt->model, requested, use);
    BuiltinMesh input = loadMeshSpec(opt->mesh, opt->normals.options(), &budget);
    if (const std::optional<std::string> repaired = repairWarning(input.mesh, opt->mesh))
      fmt::print(stderr, "warning: {}\n", *repaired);
    auto mesh = std::make_shared<const TriangleMesh>(std::move(input.mesh));
    const auto start = std::chrono::steady_clock::now();
    const std::unique_ptr<SurfaceModel> model = makeModel(opt->model, mesh);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (const std::optional<std::string> warning = conversionWarning(*model, input.description))
      fmt::print(stderr, "warning: {}\n", *warning);
    // A tessellation written as triangles, or a tessellated model's (which it renders), is
    // resolved to the level it uses, as Python's Model does; other patch files name the request.
    const Tessellation tessellation = writesPatches ? renderTessellation(*model, requested)
                                                    : resolveTessellation(*model, requested);
    if (!writesPatches)
      chargeResolvedTessellation(budget, opt->model, requested, tessellation, use,
                                 mesh->triangleCount(), opt->mesh);
    const size_t written = writeConversion(*model, tessellation, opt->output);
    // The models that keep the input triangles write them as they are: no lattice to name.
    const bool lattice = model->representation() != Representation::InputTriangles;
    const std::string what =
        written == 0 ? fmt::format("{} patches", model->patchCount())
        : lattice    ? fmt::format("{} triangles, tessellation {}{}", written,
                                   tessellationName(tessellation),
                                requested.kind == Tessellation::Kind::Adaptive ? " (auto)" : "")
                     : fmt::format("{} triangles", written);
    fmt::print("{}: {} model of {} ({} input triangles -> {}; converted in {:.3f} s)\n",
               opt->output, opt->model, input.description, mesh->triangleCount(), what, seconds);
    return 0;
  };
}

}  // namespace quadtri::cli
