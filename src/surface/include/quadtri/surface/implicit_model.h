// `quadric-implicit`: the thesis' implicit quadric triangle (§4.3), rendered by direct ray–quadric
// intersection.
#pragma once

#include <vector>

#include "quadtri/surface/edge_curves.h"
#include "quadtri/surface/model.h"
#include "quadtri/surface/quadric_patch.h"

namespace quadtri {

/// Each triangle becomes the quadric f_i = 0 fitted by the thesis' least squares to its §4.2
/// parametric patch f_p (implicit_fit.h), clipped by the thesis' four planes and by an
/// axis-aligned box. The thesis had no box; here it is the box of the patch's own surface: the
/// 15 points of a triangular lattice of f_p with 4 steps per side, projected onto the quadric
/// along f_p's normal (only those inside the planes), plus the triangle's corners, inflated by
/// 5% of the triangle's longest edge so the sheet between samples stays inside. fellBack(t):
/// one of f_p's edge control points gave up its tangent planes (clamped, or a damped solve off
/// them: edge_curves.h).
class ImplicitModel final : public SurfaceModel {
 public:
  /// Each patch is clipped to the box of its sampled points grown by 5% of its longest edge;
  /// with `exactBoxes` (the default) the box it stores is then the exact box of its points
  /// inside that one (tightPatchBounds), which gives the same hits and fewer ray tests.
  explicit ImplicitModel(std::shared_ptr<const TriangleMesh> mesh, bool exactBoxes = true);
  std::string_view name() const override { return "quadric-implicit"; }
  /// f_p(u,v) moved along f_p's unit normal to the nearest root of the ray–quadric equation,
  /// with the quadric's unit gradient oriented to the shading normals. Where no root lies
  /// within one longest edge of f_p(u,v) (the quadric misses that part of the patch), f_p(u,v)
  /// itself with f_p's normal is returned.
  SurfacePoint evaluate(size_t t, double u, double v) const override;
  void evaluateMany(size_t t, const Vec2* uv, size_t count, SurfacePoint* out) const override;
  void positions(size_t t, const Vec2* uv, size_t count, Vec3* out) const override;
  Representation representation() const override { return Representation::Implicit; }
  const std::vector<QuadricPatch>& renderPatches() const override { return patches_; }
  size_t patchMemoryBytes() const override { return sizeof(QuadricPatch) * patches_.size(); }
  /// {"quadric": [A..J], "planes": [[nx,ny,nz,d], ...], "bounds": {"min", "max"},
  ///  "parametric": {"c": [c0..c5]}, "control_points": [b01, b12, b20]}.
  void patchRecord(size_t t, PatchRecord& out) const override;

  /// The §4.2 parametric patch f_p that patch t was fitted to: the triangle's corners and its
  /// edges' control points, kept where they need the mesh's adjacency and computed again
  /// (localEdgeControlPoints) where they do not.
  QuadraticPatch parametricPatch(size_t t) const {
    if (controlPoints_.empty())
      return {{mesh().corner(t, 0), mesh().corner(t, 1), mesh().corner(t, 2)},
              localEdgeControlPoints(mesh(), t)};
    return quadraticPatch(mesh(), controlPoints_, t);
  }

 private:
  SurfacePoint evaluateOn(const QuadraticPatch& fp, size_t t, double u, double v) const;

  /// edgeControlPoints(), per triangle; empty where edgeControlPointsAreLocal.
  std::vector<std::array<Vec3, 3>> controlPoints_;
  std::vector<QuadricPatch> patches_;
};

}  // namespace quadtri
