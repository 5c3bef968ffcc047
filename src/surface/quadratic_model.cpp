#include "quadtri/surface/quadratic_model.h"

#include <fmt/format.h>

#include <stdexcept>

#include "quadtri/surface/local_patches.h"

namespace quadtri {

std::array<Vec3, 3> QuadraticPatchModel::computeControlPoints(size_t t) const {
  throw std::logic_error(fmt::format("{}: patch {} has no control points", name(), t));
}

SurfacePoint QuadraticPatchModel::evaluate(size_t t, double u, double v) const {
  const QuadraticPatch p = patch(t);
  Vec3 du, dv;
  p.derivatives(u, v, du, dv);
  return {p.position(u, v), orientedPatchNormal(mesh(), t, u, v, du, dv)};
}

Vec3 QuadraticPatchModel::position(size_t t, double u, double v) const {
  return patch(t).position(u, v);
}

void QuadraticPatchModel::positions(size_t t, const Vec2* uv, size_t count, Vec3* out) const {
  const QuadraticPatch p = patch(t);
  for (size_t i = 0; i < count; ++i) out[i] = p.position(uv[i].x(), uv[i].y());
}

}  // namespace quadtri
