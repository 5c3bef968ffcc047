// `quadric-implicit-robust`: one corner-exact implicit quadric per triangle, clipped by shared
// edge planes (docs/DESIGN.md §3, findings on §4.3).
#pragma once

#include <array>
#include <vector>

#include "quadtri/mesh/topology.h"
#include "quadtri/surface/edge_curves.h"
#include "quadtri/surface/model.h"
#include "quadtri/surface/quadric_patch.h"

namespace quadtri {

/// Each triangle becomes the quadric of fitQuadric (corners exact, corner normals exact on data
/// from any quadric, the sphere reproduced exactly). Two mesh-wide steps then move each quadric
/// along its pencil q + μL², which keeps the corners and their normals: where the fit leaves
/// part of the triangle uncovered (normals no quadric comes near), the member that is a graph
/// over the triangle's plane; on data from a quadric, the members on which neighbours agree
/// across their edges (sparse least squares). Each patch is clipped to
///  - three edge planes through the edge's chord, computed once per mesh edge and handed to
///    the two neighbours with opposite inside sides, so together they partition space along
///    the edge: the plane of the line pair a − κb through the edge where that is real (both
///    patches then end on the curve where their quadrics meet; exactly for data from any
///    quadric), otherwise the thesis' P_ij (spanned by vj−vi and ni+nj, from normals both
///    sides share);
///  - a slab parallel to the triangle around the patch's height range, which keeps the near
///    sheet only;
///  - a tight box: the sampled patch grown by a curvature bound on the sagitta between samples.
/// evaluate(t, u, v) projects the thesis' parametric patch f_p(u, v) onto the quadric along a
/// direction that lies in the edge plane on each edge (the start point moved into that plane),
/// so the boundary it reports is the clipped boundary.
///
/// On generic data (not from a quadric) neighbouring quadrics meet the shared plane in
/// slightly different conics (their corner normals differ by the O(h²) error that no quadric
/// through three points with three prescribed tangent planes avoids). Both conics pass through
/// the edge's two vertices, so the sliver between them is a lens pinched at its ends; an edge
/// bridge (QuadricPatch::joins) fills it with the part of the shared plane where the two
/// quadrics disagree about inside and outside, and the patches with their bridges bound a
/// closed solid. Edges where the two sides meet to round-off (data from a quadric) get none.
///
/// Where the normals are such that no member of the pencil follows them (a fold, such as the
/// ring around the teapot's knob), the quadric leaves its wedge or misses the lines evaluate
/// projects along, and its patch would not cover the triangle. Such a patch falls back to the
/// triangle's own plane (the same edge planes then clip it to the triangle), and its bridges
/// join it to its neighbours: a flat facet rather than a hole.
class RobustImplicitModel final : public SurfaceModel {
 public:
  explicit RobustImplicitModel(std::shared_ptr<const TriangleMesh> mesh);
  std::string_view name() const override { return "quadric-implicit-robust"; }
  SurfacePoint evaluate(size_t t, double u, double v) const override;
  Representation representation() const override { return Representation::Implicit; }
  const std::vector<QuadricPatch>& quadricPatches() const override { return patches_; }
  /// The patches, then one bridge per interior edge whose sides do not meet exactly.
  const std::vector<QuadricPatch>& renderPatches() const override { return primitives_; }
  size_t patchMemoryBytes() const override { return primitives_.size() * sizeof(QuadricPatch); }
  /// Number of edge bridges among renderPatches().
  size_t bridgeCount() const { return primitives_.size() - patches_.size(); }
  /// Number of patches that fell back to their triangle's plane.
  size_t flatCount() const;
  bool isFlat(size_t t) const { return frames_[t].flat; }
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
    double boundsMargin = 0.0;  ///< how far the patch may leave the hull of its samples
    bool flat = false;          ///< fell back to the triangle's plane (see the class comment)
  };
  bool coversItself(size_t t) const;
  void clipToPatch(size_t t);
  void addBridges(const MeshTopology& topo);

  std::vector<QuadricPatch> patches_;
  std::vector<QuadricPatch> primitives_;
  std::vector<Frame> frames_;
};

}  // namespace quadtri
