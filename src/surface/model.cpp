#include "quadtri/surface/model.h"

#include <fmt/ranges.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "model_cost.h"
#include "quadtri/math/error.h"
#include "quadtri/surface/bezier_triangle.h"
#include "quadtri/surface/edges_model.h"
#include "quadtri/surface/flat_model.h"
#include "quadtri/surface/g1_model.h"
#include "quadtri/surface/implicit_model.h"
#include "quadtri/surface/nagata_model.h"
#include "quadtri/surface/param_model.h"
#include "quadtri/surface/patch_record.h"
#include "quadtri/surface/phong_model.h"
#include "quadtri/surface/pn_model.h"
#include "quadtri/surface/quadric_patch.h"
#include "quadtri/surface/robust_implicit_model.h"

namespace quadtri {

nlohmann::json SurfaceModel::patchJson(size_t t) const {
  PatchRecord record;
  patchRecord(t, record);
  return record.toJson();
}

const std::vector<QuadricPatch>& SurfaceModel::renderPatches() const {
  static const std::vector<QuadricPatch> none;
  return none;
}

std::span<const QuadricPatch> SurfaceModel::quadricPatches() const {
  const std::vector<QuadricPatch>& all = renderPatches();
  return {all.data(), std::min(all.size(), patchCount())};
}

const std::vector<BezierTriangle>& SurfaceModel::bezierPieces() const {
  static const std::vector<BezierTriangle> none;
  return none;
}

void SurfaceModel::setFallbacks(std::vector<uint8_t> flags) {
  if (!flags.empty() && flags.size() != patchCount())
    fail("model '{}': {} fallback flags for {} patches", name(), flags.size(), patchCount());
  fallbackCount_ = 0;
  for (uint8_t f : flags) fallbackCount_ += f != 0;
  fallbacks_ = std::move(flags);
}

namespace {

using ModelFactory = std::unique_ptr<SurfaceModel> (*)(std::shared_ptr<const TriangleMesh>);

/// One model: its name (as `--model` takes it), how to convert a mesh with it, and what that
/// costs in memory (model_cost.h).
struct ModelEntry {
  std::string_view name;
  ModelFactory make;
  ModelCost cost;
};

template <typename M, auto... Args>
std::unique_ptr<SurfaceModel> make(std::shared_ptr<const TriangleMesh> mesh) {
  return std::make_unique<M>(std::move(mesh), Args...);
}

/// The models, in the order `--model all` lists them. Adding a model is its own files and one
/// line here; the CLI, the JSON, the CSV, the study and Python take their names from it, and the
/// memory checks its cost: {input triangles, traced, json, lattice mesh, per region, streamed}
/// (model_cost.h). The
/// lattice mesh's bytes per output triangle were measured again once the lattice was built in
/// parallel and the PLY writer stopped pairing every corner (2026-12-05: 51-74 bytes as the slope
/// of `convert icosphere:5|6 -o x.obj|x.ply` at level 8, the robust model's on levels 4 and 5),
/// and are charged about 15% above that.
constexpr ModelEntry kModels[] = {
    {"flat", make<FlatModel, FlatModel::Normals::Geometric>, {true, 100, 800, 0}},
    {"shading", make<FlatModel, FlatModel::Normals::Interpolated>, {true, 100, 800, 0}},
    {"shading-offset",
     make<FlatModel, FlatModel::Normals::InterpolatedOffset>,
     {true, 100, 800, 0}},
    {"quadric-edges",
     make<EdgesModel, EdgesModel::Blend::Transfinite>,
     {false, 0, 4500, 64, 0, 200}},
    {"quadric-param", make<ParamModel>, {false, 0, 4200, 64, 0, 200}},
    {"quadric-implicit", make<ImplicitModel>, {false, 700, 7800, 72, 0, 620}},
    // Not welded: a vertex per patch corner.
    {"quadric-edges-eq42",
     make<EdgesModel, EdgesModel::Blend::ThesisEq42>,
     {false, 0, 4500, 76, 0, 165}},
    {"quadric-implicit-robust", make<RobustImplicitModel>, {false, 3400, 9800, 88, 0, 3950}},
    {"phong", make<PhongModel>, {false, 0, 1900, 64, 0, 200}},
    {"pn", make<PnModel>, {false, 0, 6100, 64, 0, 260}},
    {"nagata", make<NagataModel>, {false, 0, 2500, 64, 0, 260}},
    {"quadric-g1", make<G1Model>, {false, 1250, 1700, 84, 330, 1390}},
};

}  // namespace

const std::vector<std::string>& modelNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const ModelEntry& m : kModels) out.emplace_back(m.name);
    return out;
  }();
  return names;
}

const ModelCost* modelCost(std::string_view name) {
  for (const ModelEntry& m : kModels)
    if (m.name == name) return &m.cost;
  return nullptr;
}

std::unique_ptr<SurfaceModel> makeModel(std::string_view name,
                                        std::shared_ptr<const TriangleMesh> mesh) {
  for (const ModelEntry& m : kModels)
    if (m.name == name) return m.make(std::move(mesh));
  fail("unknown model '{}': expected one of {}", name, fmt::join(modelNames(), ", "));
}

}  // namespace quadtri
