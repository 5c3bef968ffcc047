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
///  - three edge planes through the edge's chord, computed once per mesh edge and handed to
///    the two neighbours with opposite inside sides, so together they partition space along
///    the edge: the plane through the point where the neighbours' quadrics cross near the
///    edge's middle (so both end on the same curve; exact for data from any quadric), or where
///    they do not cross, the thesis' P_ij (spanned by vj−vi and ni+nj, from normals both sides
///    share);
///  - a slab parallel to the triangle around the patch's height range, which keeps the near
///    sheet only;
///  - a tight box: the sampled patch grown by a curvature bound on the sagitta between samples.
/// evaluate(t, u, v) projects the thesis' parametric patch f_p(u, v) onto the quadric along a
/// direction that lies in the edge plane on each edge (the start point moved into that plane),
/// so the boundary it reports is the clipped boundary.
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
    std::array<Vec4, 3> edgePlane;
    Vec3 faceNormal;
    double cornerNormalErrorDeg = 0.0;
  };
  SurfacePoint project(size_t t, double u, double v, bool& onQuadric) const;
  void clipToPatch(size_t t);

  std::vector<QuadricPatch> patches_;
  std::vector<Frame> frames_;
};

}  // namespace quadtri
