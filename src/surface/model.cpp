#include "surface/model.h"

#include <fmt/ranges.h>

#include "math/error.h"
#include "surface/flat_model.h"
#include "surface/implicit_model.h"
#include "surface/nagata_model.h"
#include "surface/phong_model.h"
#include "surface/pn_model.h"
#include "surface/quadric_patch.h"

namespace quadtri {

const std::vector<QuadricPatch>& SurfaceModel::quadricPatches() const {
  static const std::vector<QuadricPatch> none;
  return none;
}

const std::vector<std::string>& modelNames() {
  static const std::vector<std::string> names = {
      "flat",
      "shading",
      "quadric-implicit",
      "phong",
      "pn",
      "nagata",
  };
  return names;
}

std::unique_ptr<SurfaceModel> makeModel(std::string_view name, std::shared_ptr<const TriangleMesh> mesh) {
  if (name == "flat") return std::make_unique<FlatModel>(std::move(mesh), false);
  if (name == "shading") return std::make_unique<FlatModel>(std::move(mesh), true);
  if (name == "quadric-implicit") return std::make_unique<ImplicitModel>(std::move(mesh));
  if (name == "phong") return std::make_unique<PhongModel>(std::move(mesh));
  if (name == "pn") return std::make_unique<PnModel>(std::move(mesh));
  if (name == "nagata") return std::make_unique<NagataModel>(std::move(mesh));
  fail("unknown model '{}': expected one of {}", name, fmt::join(modelNames(), ", "));
}

}  // namespace quadtri
