// The convex cell each patch of `quadric-implicit-robust` lives in, and exact bounds and sign
// checks of a quadric on it (DESIGN.md §3, findings on §4.3).
#pragma once

#include <vector>

#include "quadtri/math/vec.h"
#include "quadtri/surface/quadric_patch.h"

namespace quadtri {

/// The convex polytope {x : n_i·x + d_i >= 0 for every plane i}, as its vertices and, per plane,
/// the polygon of vertices on it in cyclic order (empty for a plane that only touches the
/// polytope in an edge or a vertex, or not at all). Unit plane normals expected.
struct ConvexCell {
  std::vector<Vec4> planes;
  std::vector<Vec3> vertices;
  std::vector<std::vector<int>> faces;  ///< per plane, indices into vertices
  double tolerance = 0.0;               ///< distance within which a point counts as on a plane

  bool empty() const { return vertices.empty(); }
  /// Inside every plane, to within the tolerance.
  bool contains(const Vec3& p) const;
  Bounds3 bounds() const;
};

/// Vertices (triple intersections of the planes inside all of them) and faces. `tolerance` is
/// an absolute length (a small multiple of the round-off of the cell's size).
ConvexCell makeConvexCell(const std::vector<Vec4>& planes, double tolerance);

/// Exact axis-aligned bounds of {q = 0} ∩ cell (empty when they do not meet): the box of the
/// candidate extreme points, which are the points of the set where a coordinate is extremal on
/// the surface (∇q parallel to an axis), on a face's conic (its gradient in the face parallel to
/// the axis' projection) or where the surface crosses an edge of the cell. Where such critical
/// points form a line or a plane the extreme is also met on the cell's boundary, which the
/// other candidates cover.
Bounds3 quadricBoundsInCell(const QuadricCoeffs& q, const ConvexCell& cell);

/// Least and greatest dir·x over {q = 0} ∩ cell ({+inf, -inf} when they do not meet), from
/// the same candidates as quadricBoundsInCell.
std::pair<double, double> quadricRangeInCell(const QuadricCoeffs& q, const ConvexCell& cell,
                                             const Vec3& dir);

/// Exact axis-aligned bounds of {x on face f of the cell : (sign·q(x) < 0) != (base·x < 0)}:
/// the part of the face between the quadric's conic and the base plane's line. Empty where
/// the two agree on the whole face.
Bounds3 betweenBoundsOnFace(const QuadricCoeffs& q, double sign, const Vec4& base,
                            const ConvexCell& cell, int f);

/// Least and greatest value of q over the polygon of face f (exact: vertices, extremes along
/// its edges and the conic's centre when inside). {+inf, -inf} for a face without polygon.
std::pair<double, double> quadricRangeOnFace(const QuadricCoeffs& q, const ConvexCell& cell, int f);

/// True where the interiors of two cells overlap by more than `tolerance` (separating axis
/// test over both cells' face normals and the cross products of their edges; cells that only
/// touch do not overlap).
bool cellsOverlap(const ConvexCell& a, const ConvexCell& b, double tolerance);

/// Value of q along the line o + s·d: the coefficients (a, b, c) of a s² + b s + c.
void quadricAlongLine(const QuadricCoeffs& q, const Vec3& o, const Vec3& d, double& a, double& b,
                      double& c);

}  // namespace quadtri
