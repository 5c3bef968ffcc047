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

/// A model with three edge control points per triangle (the corners are the mesh's) that
/// evaluates the quadratic Bézier triangle they make: the position, and the normal ∂u × ∂v
/// oriented by the corner normals (orientedPatchNormal). It keeps the points (72 bytes a
/// triangle), or, where they follow cheaply from the triangle alone, computes them when asked.
class QuadraticPatchModel : public SurfaceModel {
 public:
  SurfacePoint evaluate(size_t t, double u, double v) const final;
  void evaluateMany(size_t t, const Vec2* uv, size_t count, SurfacePoint* out) const final;
  Vec3 position(size_t t, double u, double v) const final;
  void positions(size_t t, const Vec2* uv, size_t count, Vec3* out) const final;

  /// The quadratic Bézier triangle of triangle t (edge k joins corners k and k+1).
  QuadraticPatch patch(size_t t) const {
    const TriangleMesh& m = mesh();
    return QuadraticPatch{{m.corner(t, 0), m.corner(t, 1), m.corner(t, 2)}, controlPoints(t)};
  }
  /// Triangle t's edge control points: the kept ones, or computeControlPoints(t).
  std::array<Vec3, 3> controlPoints(size_t t) const {
    return controlPoints_.empty() ? computeControlPoints(t) : controlPoints_[t];
  }

 protected:
  explicit QuadraticPatchModel(std::shared_ptr<const TriangleMesh> mesh)
      : SurfaceModel(std::move(mesh)) {}
  /// Each triangle's edge control points, filled by the model's constructor; left empty by a
  /// model that computes them when asked (computeControlPoints).
  std::vector<std::array<Vec3, 3>> controlPoints_;
  /// Triangle t's edge control points where controlPoints_ is empty: the model's own rule,
  /// bit for bit what its constructor would have kept. The base has none to compute (an
  /// empty controlPoints_ then means a mesh without triangles) and throws.
  virtual std::array<Vec3, 3> computeControlPoints(size_t t) const;
};

}  // namespace quadtri
