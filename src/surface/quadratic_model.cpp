#include "quadtri/surface/quadratic_model.h"

#include <fmt/format.h>

#include <stdexcept>

#include "quadtri/surface/local_patches.h"

namespace quadtri {

std::array<Vec3, 3> QuadraticPatchModel::computeControlPoints(size_t t) const {
  throw std::logic_error(fmt::format("{}: patch {} has no control points", name(), t));
}

namespace {

SurfacePoint evaluatePatch(const TriangleMesh& mesh, const QuadraticPatch& p, size_t t, double u,
                           double v) {
  Vec3 du, dv;
  p.derivatives(u, v, du, dv);
  return {p.position(u, v), orientedPatchNormal(mesh, t, u, v, du, dv)};
}

}  // namespace

SurfacePoint QuadraticPatchModel::evaluate(size_t t, double u, double v) const {
  return evaluatePatch(mesh(), patch(t), t, u, v);
}

void QuadraticPatchModel::evaluateMany(size_t t, const Vec2* uv, size_t count,
                                       SurfacePoint* out) const {
  const QuadraticPatch p = patch(t);
  for (size_t i = 0; i < count; ++i) out[i] = evaluatePatch(mesh(), p, t, uv[i].x(), uv[i].y());
}

Vec3 QuadraticPatchModel::position(size_t t, double u, double v) const {
  return patch(t).position(u, v);
}

void QuadraticPatchModel::positions(size_t t, const Vec2* uv, size_t count, Vec3* out) const {
  const QuadraticPatch p = patch(t);
  for (size_t i = 0; i < count; ++i) out[i] = p.position(uv[i].x(), uv[i].y());
}

}  // namespace quadtri
