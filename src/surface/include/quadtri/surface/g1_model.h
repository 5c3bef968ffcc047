// `quadric-g1`: a G1 surface from a triangle mesh and its vertex normals, each triangle split
// Clough–Tocher into three quartic Bézier pieces (docs/DESIGN.md §13).
#pragma once

#include <array>
#include <vector>

#include "quadtri/surface/bezier_triangle.h"
#include "quadtri/surface/creases.h"
#include "quadtri/surface/model.h"

namespace quadtri {

/// The three pieces of one triangle with corners p and unit corner normals n (ends: the
/// triangle's edgeEnds, or null for an isolated triangle). Piece k spans (p_k, p_{k+1}, c), c
/// the centroid, in the macro triangle's barycentric domain.
///
/// - Each edge is the cubic Bézier of PN triangles, p_a + T_ab/3 next to p_a with T_ab the
///   chord's tangent part at p_a (its projection onto the tangent plane, or onto the crease
///   line at a crease end), raised to degree 4. It depends only on data both sides share.
/// - Each corner's first ring lies in the corner's tangent plane: the vertex normal is exact.
/// - Across each edge the derivative D(t) towards the centroid is κ(t) a(t) + η(t) b'(t): b the
///   edge, a(t) the linear blend of the unit transversals α = n × T at its ends (shared by both
///   sides where both sides share the end normals), κ, η linear and fitted at the corners. Both
///   sides' tangent planes along the edge are then span(b', a): the surface is G1 across every
///   edge whose two sides share both end normals, and C0 across creases.
/// - Inside the triangle the three pieces join C1 (the Clough–Tocher conditions), their
///   internal edges chosen as degree-raised cubics.
/// `gaveUp`, when given, is set where an edge end has no transversal (a chord along the normal)
/// and the cross-edge derivative was left as the corners' own (C0 only there).
std::array<BezierTriangle, 3> g1Pieces(const std::array<Vec3, 3>& p, const std::array<Vec3, 3>& n,
                                       const std::array<std::array<EdgeEnd, 2>, 3>* ends,
                                       bool* gaveUp = nullptr);

/// Which piece of a macro triangle holds barycentric (u, v), and the piece's own (u, v) there.
struct G1PieceCoords {
  int piece;
  double u, v;
};
G1PieceCoords g1PieceCoords(double u, double v);

class G1Model final : public SurfaceModel {
 public:
  explicit G1Model(std::shared_ptr<const TriangleMesh> mesh);
  std::string_view name() const override { return "quadric-g1"; }
  SurfacePoint evaluate(size_t t, double u, double v) const override;
  Representation representation() const override { return Representation::Bezier; }
  const std::vector<BezierTriangle>& bezierPieces() const override { return pieces_; }
  size_t patchMemoryBytes() const override { return pieces_.size() * sizeof(BezierTriangle); }
  void patchRecord(size_t t, PatchRecord& out) const override;

  const BezierTriangle& piece(size_t t, int k) const { return pieces_[3 * t + size_t(k)]; }

 private:
  std::vector<BezierTriangle> pieces_;
};

}  // namespace quadtri
