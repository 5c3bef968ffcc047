// The models whose patch is a quadratic Bézier triangle through the mesh's corners with three
// edge control points per triangle (`quadric-param`, `phong`, `nagata`): what they store and how
// a patch is evaluated, written once.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "quadtri/surface/edge_curves.h"
#include "quadtri/surface/model.h"

namespace quadtri {

/// A model that keeps three edge control points per triangle (72 bytes; the corners are the
/// mesh's) and evaluates the quadratic Bézier triangle they make: the position, and the normal
/// ∂u × ∂v oriented by the corner normals (orientedPatchNormal).
class QuadraticPatchModel : public SurfaceModel {
 public:
  SurfacePoint evaluate(size_t t, double u, double v) const final;
  Vec3 position(size_t t, double u, double v) const final;
  void positions(size_t t, const Vec2* uv, size_t count, Vec3* out) const final;

  /// The quadratic Bézier triangle of triangle t (edge k joins corners k and k+1).
  QuadraticPatch patch(size_t t) const { return quadraticPatch(mesh(), controlPoints_, t); }

 protected:
  explicit QuadraticPatchModel(std::shared_ptr<const TriangleMesh> mesh)
      : SurfaceModel(std::move(mesh)) {}
  /// Each triangle's edge control points, filled by the model's constructor.
  std::vector<std::array<Vec3, 3>> controlPoints_;
};

}  // namespace quadtri
