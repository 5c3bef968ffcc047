#include "quadtri/surface/param_model.h"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "quadtri/surface/local_patches.h"

namespace quadtri {

ParamModel::ParamModel(std::shared_ptr<const TriangleMesh> mesh) : SurfaceModel(std::move(mesh)) {
  std::vector<uint8_t> fallbacks;
  controlPoints_ = edgeControlPoints(this->mesh(), &fallbacks);
  setFallbacks(std::move(fallbacks));
}

SurfacePoint ParamModel::evaluate(size_t t, double u, double v) const {
  const QuadraticPatch p = patch(t);
  Vec3 pu, pv;
  p.derivatives(u, v, pu, pv);
  return {p.position(u, v), orientedPatchNormal(mesh(), t, u, v, pu, pv)};
}

Vec3 ParamModel::position(size_t t, double u, double v) const {
  return patch(t).position(u, v);
}

void ParamModel::positions(size_t t, const Vec2* uv, size_t count, Vec3* out) const {
  const QuadraticPatch p = patch(t);
  for (size_t i = 0; i < count; ++i) out[i] = p.position(uv[i].x(), uv[i].y());
}

nlohmann::json ParamModel::patchJson(size_t t) const {
  return quadraticPatchJson(patch(t));
}

}  // namespace quadtri
