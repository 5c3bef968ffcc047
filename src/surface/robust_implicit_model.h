// `quadric-implicit-robust`: one corner-exact implicit quadric per triangle, clipped by shared
// edge planes (DESIGN.md §3, findings on §4.3).
#pragma once

#include <array>
#include <vector>

#include "surface/edge_curves.h"
#include "surface/model.h"
#include "surface/quadric_patch.h"

namespace quadtri {

/// Each triangle becomes the quadric of fitQuadric (corners exact, corner normals exact on data
/// from any quadric, the sphere reproduced exactly) clipped to
///  - its three edge planes P_ij (through vi, vj, spanned by vj−vi and ni+nj, from normals both
///    sides share): each is computed once per mesh edge and handed to the two neighbours with
///    opposite inside sides, so together they partition space along the edge;
///  - a slab parallel to the triangle around the patch's height range, which keeps the near
///    sheet only;
///  - a tight box: the sampled patch grown by a curvature bound on the sagitta between samples.
/// evaluate(t, u, v) projects the thesis' parametric patch f_p(u, v) onto the quadric along a
/// direction that lies in P_ij on edge ij, so the boundary it reports is the clipped boundary.
class RobustImplicitModel final : public SurfaceModel {
 public:
  explicit RobustImplicitModel(std::shared_ptr<const TriangleMesh> mesh);
  std::string_view name() const override { return "quadric-implicit-robust"; }
  SurfacePoint evaluate(size_t t, double u, double v) const override;
  Representation representation() const override { return Representation::Implicit; }
  const std::vector<QuadricPatch>& quadricPatches() const override { return patches_; }
  size_t patchMemoryBytes() const override { return patches_.size() * sizeof(QuadricPatch); }
  nlohmann::json patchJson(size_t t) const override;

  /// Largest angle (degrees) between the quadric's normal at a corner of patch t and the
  /// corner's shading normal (0 up to round-off on data sampled from a quadric).
  double cornerNormalErrorDeg(size_t t) const { return frames_[t].cornerNormalErrorDeg; }

 private:
  /// What evaluate needs beyond the quadric: f_p, the projection direction in each edge plane
  /// and the unit face normal (oriented to the shading normals).
  struct Frame {
    QuadraticPatch parametric;
    std::array<Vec3, 3> edgeDirection;
    Vec3 faceNormal;
    double cornerNormalErrorDeg = 0.0;
  };
  SurfacePoint project(size_t t, double u, double v, bool& onQuadric) const;
  void clipToPatch(size_t t);

  std::vector<QuadricPatch> patches_;
  std::vector<Frame> frames_;
};

}  // namespace quadtri
