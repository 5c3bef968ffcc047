#include "quadtri/surface/param_model.h"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "quadtri/surface/local_patches.h"

namespace quadtri {

ParamModel::ParamModel(std::shared_ptr<const TriangleMesh> mesh)
    : QuadraticPatchModel(std::move(mesh)) {
  std::vector<uint8_t> fallbacks;
  controlPoints_ = edgeControlPoints(this->mesh(), &fallbacks);
  setFallbacks(std::move(fallbacks));
}

nlohmann::json ParamModel::patchJson(size_t t) const {
  return quadraticPatchJson(patch(t));
}

}  // namespace quadtri
