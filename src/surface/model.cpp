#include "surface/model.h"

#include <fmt/ranges.h>

#include "math/error.h"
#include "surface/flat_model.h"
#include "surface/quadric_patch.h"
#include "surface/robust_implicit_model.h"

namespace quadtri {

const std::vector<QuadricPatch>& SurfaceModel::quadricPatches() const {
  static const std::vector<QuadricPatch> none;
  return none;
}

const std::vector<std::string>& modelNames() {
  static const std::vector<std::string> names = {"flat", "shading", "quadric-implicit-robust"};
  return names;
}

std::unique_ptr<SurfaceModel> makeModel(std::string_view name,
                                        std::shared_ptr<const TriangleMesh> mesh) {
  if (name == "flat") return std::make_unique<FlatModel>(std::move(mesh), false);
  if (name == "shading") return std::make_unique<FlatModel>(std::move(mesh), true);
  if (name == "quadric-implicit-robust")
    return std::make_unique<RobustImplicitModel>(std::move(mesh));
  fail("unknown model '{}': expected one of {}", name, fmt::join(modelNames(), ", "));
}

}  // namespace quadtri
