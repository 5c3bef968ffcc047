#include "quadtri/surface/model.h"

#include <fmt/ranges.h>

#include "quadtri/math/error.h"
#include "quadtri/surface/bezier_triangle.h"
#include "quadtri/surface/edges_model.h"
#include "quadtri/surface/flat_model.h"
#include "quadtri/surface/g1_model.h"
#include "quadtri/surface/implicit_model.h"
#include "quadtri/surface/nagata_model.h"
#include "quadtri/surface/param_model.h"
#include "quadtri/surface/phong_model.h"
#include "quadtri/surface/pn_model.h"
#include "quadtri/surface/quadric_patch.h"
#include "quadtri/surface/robust_implicit_model.h"

namespace quadtri {

const std::vector<QuadricPatch>& SurfaceModel::quadricPatches() const {
  static const std::vector<QuadricPatch> none;
  return none;
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

const std::vector<std::string>& modelNames() {
  static const std::vector<std::string> names = {
      "flat",
      "shading",
      "shading-offset",
      "quadric-edges",
      "quadric-param",
      "quadric-implicit",
      "quadric-edges-eq42",
      "quadric-implicit-robust",
      "phong",
      "pn",
      "nagata",
      "quadric-g1",
  };
  return names;
}

std::unique_ptr<SurfaceModel> makeModel(std::string_view name,
                                        std::shared_ptr<const TriangleMesh> mesh) {
  if (name == "flat")
    return std::make_unique<FlatModel>(std::move(mesh), FlatModel::Normals::Geometric);
  if (name == "shading")
    return std::make_unique<FlatModel>(std::move(mesh), FlatModel::Normals::Interpolated);
  if (name == "shading-offset")
    return std::make_unique<FlatModel>(std::move(mesh), FlatModel::Normals::InterpolatedOffset);
  if (name == "quadric-edges")
    return std::make_unique<EdgesModel>(std::move(mesh), EdgesModel::Blend::Transfinite);
  if (name == "quadric-param") return std::make_unique<ParamModel>(std::move(mesh));
  if (name == "quadric-implicit") return std::make_unique<ImplicitModel>(std::move(mesh));
  if (name == "quadric-edges-eq42")
    return std::make_unique<EdgesModel>(std::move(mesh), EdgesModel::Blend::ThesisEq42);
  if (name == "quadric-implicit-robust")
    return std::make_unique<RobustImplicitModel>(std::move(mesh));
  if (name == "phong") return std::make_unique<PhongModel>(std::move(mesh));
  if (name == "pn") return std::make_unique<PnModel>(std::move(mesh));
  if (name == "nagata") return std::make_unique<NagataModel>(std::move(mesh));
  if (name == "quadric-g1") return std::make_unique<G1Model>(std::move(mesh));
  fail("unknown model '{}': expected one of {}", name, fmt::join(modelNames(), ", "));
}

}  // namespace quadtri
