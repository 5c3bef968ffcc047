// `quadric-implicit-robust`: one corner-exact implicit quadric per triangle, clipped by shared
// edge planes (docs/DESIGN.md §3, findings on §4.3).
#pragma once

#include <array>
#include <vector>

#include "quadtri/mesh/topology.h"
#include "quadtri/surface/edge_curves.h"
#include "quadtri/surface/model.h"
#include "quadtri/surface/quadric_patch.h"
#include "quadtri/surface/robust_cell.h"

namespace quadtri {

/// Each triangle becomes the quadric of fitQuadric (corners exact, corner normals exact on data
/// from any quadric, the sphere reproduced exactly). Two mesh-wide steps then move each quadric
/// along its pencil q + μL², which keeps the corners and their normals: where the fit leaves
/// part of the triangle uncovered (normals no quadric comes near), the member that is a graph
/// over the triangle's plane; on data from a quadric, the members on which neighbours agree
/// across their edges (sparse least squares).
///
/// Each patch lives in a convex cell: three edge planes through the edge's chord, computed once
/// per mesh edge and handed to the two neighbours with opposite inside sides (where both fits
/// are corner-exact, data from a quadric, the plane of the line pair a − κb through the edge,
/// on which both patches end exactly on the curve where their quadrics meet; otherwise the
/// thesis' P_ij, spanned by vj−vi and ni+nj; turned away from the faces where it comes within
/// 10° of one), and a slab
/// parallel to the triangle around the patch's height range. The cell's section by the
/// triangle's plane is the triangle.
///
/// Watertight by construction. The model's solid is the flat mesh's solid changed (symmetric
/// difference) by, in every cell, the region between the patch's quadric and the triangle's
/// plane. Its boundary is the flat triangles (each cancelled by its cell's section: the
/// triangle), every quadric inside its cell, and on every cell face the part of the face where
/// that region meets it. The cells need not fit together: on a face two neighbours share, their
/// two parts cancel where they coincide and the rest is the edge's bridge
/// (QuadricPatch::joins, bridgeCovers): for smooth data the lens between the two conics. A
/// patch is accepted only where its cell proves it needs nothing else: the oriented gradient
/// has a positive component along the face normal at every vertex of the cell (so inside the
/// cell the quadric is one sheet, a graph over the triangle's plane) and the quadric keeps one
/// sign on each slab face (it stays inside the slab). So the patches and bridges bound a
/// closed solid for any data; edges where the two sides meet exactly (data from a quadric)
/// need no bridge.
///
/// The cores of two cells whose triangles share no vertex (each cell cut down to the heights
/// of its patch and of the region between the patch and the triangle) must not overlap, unless
/// the triangles themselves cross, face within 60° of each other, or lie in different parts
/// (connected across edges): where cores overlap (thin parts, a plate thinner than its
/// triangles) the patch of one side would reach through the other's. Such patches are chosen again,
/// in rounds, each allowed half the reach of the last (first only the farther-reaching patch of
/// each pair, then both). A patch may also rise no farther from its triangle than the larger of
/// half its least altitude and twice its edges' largest arc sagitta.
///
/// Where the fit fails those checks or does not cover its triangle (normals that no quadric
/// through the corners follows: folds, averaged normals across sharp edges), the patch falls
/// back, keeping as much as it can: the pencil's graph member, then other members q + μL²
/// (corners and corner normals kept), then fits to corner normals blended towards the face
/// normal (corners still exact), and last the triangle's own plane.
/// evaluate(t, u, v) projects the thesis' parametric patch f_p(u, v) onto the quadric along a
/// direction that lies in the edge plane on each edge (the start point moved into that plane),
/// so the boundary it reports is the clipped boundary.
/// fellBack(t): patch t gave up its corner normals (blended, or its triangle's plane), or its
/// triangle has no extent (QuadricFit::pointFallback).
class RobustImplicitModel final : public SurfaceModel {
 public:
  explicit RobustImplicitModel(std::shared_ptr<const TriangleMesh> mesh);
  std::string_view name() const override { return "quadric-implicit-robust"; }
  SurfacePoint evaluate(size_t t, double u, double v) const override;
  Vec3 position(size_t t, double u, double v) const override;
  Representation representation() const override { return Representation::Implicit; }
  /// The patches, then one bridge per interior edge whose sides do not meet exactly.
  const std::vector<QuadricPatch>& renderPatches() const override { return patches_; }
  size_t patchMemoryBytes() const override { return patches_.size() * sizeof(QuadricPatch); }
  /// Number of edge bridges among renderPatches().
  size_t bridgeCount() const { return patches_.size() - patchCount(); }
  /// Number of patches that fell back to their triangle's plane.
  size_t flatCount() const;
  bool isFlat(size_t t) const { return frames_[t].flat; }
  /// Number of patches fitted to corner normals blended towards the face normal.
  size_t blendedCount() const;
  /// The blend of patch t's corner normals towards its face normal: 0 for the fit to the
  /// shading normals, 1 for the triangle's plane.
  double blend(size_t t) const { return frames_[t].blend; }
  void patchRecord(size_t t, PatchRecord& out) const override;

  /// Largest angle (degrees) between the quadric's normal at a corner of patch t and the
  /// corner's shading normal (0 up to round-off on data sampled from a quadric).
  double cornerNormalErrorDeg(size_t t) const { return frames_[t].cornerNormalErrorDeg; }

 private:
  /// What evaluate needs beyond the quadric: f_p (its control points), the projection direction in
  /// each edge plane and the unit face normal, on the side of its part of the mesh that most
  /// shading normals point to (the winding, made consistent across the part: faceSides).
  struct Frame {
    /// The edge control points of the thesis' parametric patch f_p; its corners are the mesh's.
    std::array<Vec3, 3> controlPoints;
    std::array<Vec3, 3> edgeDirection;
    /// The edge's two sides have different corner normals at an end (a crease splits them).
    std::array<bool, 3> crease{};
    Vec3 faceNormal;
    double cornerNormalErrorDeg = 0.0;
    double blend = 0.0;  ///< normals blended this far towards the face normal (1: flat)
    /// Heights (along the face normal, from the triangle's plane) between which the patch and
    /// the region between it and the triangle lie; reach is the larger of their sizes.
    double coreLo = 0.0, coreHi = 0.0, reach = 0.0;
    bool flat = false;  ///< fell back to the triangle's plane (see the class comment)
  };
  /// position(t, u, v) in two steps: the line through f_p(u, v), moved into the edge planes,
  /// along which it is projected (it depends on the triangle only), then the point where that
  /// line meets q.
  struct LiftLine {
    Vec3 start, dir;
  };
  LiftLine liftLine(size_t t, double u, double v) const;
  static LiftLine liftLineOn(const QuadraticPatch& parametric, const QuadricPatch& patch,
                             const Frame& frame, double u, double v);
  static Vec3 liftOnto(const QuadricCoeffs& q, const LiftLine& line);
  /// Samples per edge of the lattice of lines along which a candidate's heights over its
  /// triangle are sampled, and the lines themselves, built once per triangle for all of its
  /// candidates.
  static constexpr int kHeightSamples = 12;
  using HeightLattice = std::array<LiftLine, (kHeightSamples + 1) * (kHeightSamples + 2) / 2>;
  void heightLattice(size_t t, HeightLattice& lattice) const;
  /// Makes q patch t's quadric if its cell passes the checks of the class comment (and it
  /// covers the triangle); fills `cell` and the patch's slab, orientation and bounds.
  /// `reach` caps how far the patch may reach from the triangle's plane.
  bool tryQuadric(size_t t, const QuadricCoeffs& q, const HeightLattice& lattice, double reach,
                  ConvexCell& cell);
  void makeFlat(size_t t, double reach, ConvexCell& cell);
  void choosePatch(size_t t, const QuadricCoeffs& fitted, const QuadricCoeffs& pencil, double reach,
                   ConvexCell& cell);
  /// What the bridges need of a triangle's final cell, kept instead of the cell (656 bytes):
  /// for each edge k, the box of the region between the patch and its base on the cell's face
  /// k (betweenBoundsOnFace; empty without a base), and the cell's tolerance, from which its
  /// core is built again.
  struct CellSummary {
    std::array<Bounds3, 3> faceBoxes;
    double tolerance = 0.0;
    bool hasCell = false;
    bool empty() const { return !hasCell; }
  };
  /// Chooses triangle t's patch (choosePatch) and summarises its cell.
  CellSummary chooseAndSummarise(size_t t, const QuadricCoeffs& fitted, const QuadricCoeffs& pencil,
                                 double reach);
  void addBridges(const MeshTopology& topo, const std::vector<CellSummary>& cells);

  /// The construction (the constructor's work), on geometry().
  void construct(const MeshTopology& topo);
  /// Moves every patch, bridge and frame built on a mesh moved by −origin back to the world.
  void translateToWorld(const Vec3& origin);
  /// The mesh the construction works on: mesh() moved to near the origin where it lies far
  /// from it (frameOrigin of its box), else mesh() itself. After the
  /// construction, mesh().
  const TriangleMesh& geometry() const { return construction_ ? *construction_ : mesh(); }
  const TriangleMesh* construction_ = nullptr;
  /// Where geometry()'s origin lies in the world during the construction (zero otherwise).
  Vec3 worldOrigin_ = Vec3::Zero();

  /// One patch per triangle, then the bridges (one array: the renderer traces it whole).
  std::vector<QuadricPatch> patches_;
  std::vector<Frame> frames_;
};

}  // namespace quadtri
