#include "surface/param_model.h"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "surface/local_patches.h"

namespace quadtri {

ParamModel::ParamModel(std::shared_ptr<const TriangleMesh> mesh)
    : SurfaceModel(std::move(mesh)), controlPoints_(edgeControlPoints(this->mesh())) {}

SurfacePoint ParamModel::evaluate(size_t t, double u, double v) const {
  const QuadraticPatch p = patch(t);
  Vec3 pu, pv;
  p.derivatives(u, v, pu, pv);
  return {p.position(u, v), orientedPatchNormal(mesh(), t, u, v, pu, pv)};
}

nlohmann::json ParamModel::patchJson(size_t t) const {
  const QuadraticPatch p = patch(t);
  nlohmann::json j;
  for (const Vec3& corner : p.v) j["vertices"].push_back(vecJson(corner));
  j["control_points"] = {
      {"b01", vecJson(p.b[0])}, {"b12", vecJson(p.b[1])}, {"b20", vecJson(p.b[2])}};
  const std::array<Vec3, 6> c = p.coefficients();
  for (int k = 0; k < 6; ++k) j["coefficients"][fmt::format("c{}", k)] = vecJson(c[k]);
  return j;
}

}  // namespace quadtri
