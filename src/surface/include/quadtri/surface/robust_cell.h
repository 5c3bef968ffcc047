// The convex cell each patch of `quadric-implicit-robust` lives in, and exact bounds and sign
// checks of a quadric on it (DESIGN.md §3, findings on §4.3).
#pragma once

#include <span>
#include <vector>

#include "quadtri/math/fixed_vector.h"
#include "quadtri/math/vec.h"
#include "quadtri/surface/quadric_patch.h"

namespace quadtri {

/// The convex polytope {x : n_i·x + d_i >= 0 for every plane i}, as its vertices and, per plane,
/// the polygon of vertices on it in cyclic order (empty for a plane that only touches the
/// polytope in an edge or a vertex, or not at all). Unit plane normals expected.
///
/// Stored inline, without allocation: a cell is built for every triangle (three times over),
/// and per-cell heap vectors were a fifth of the model's conversion time.
struct ConvexCell {
  /// A patch's clip planes and one more (the fold check of a patch's cell adds a plane) are
  /// the most a cell is built from.
  static constexpr size_t kMaxPlanes = QuadricPatch::kMaxPlanes + 1;
  /// A simple polytope of n faces has at most 2n − 4 vertices (10 here). Points within the
  /// tolerance of a plane count as on it, so nearly concurrent planes can leave a distinct
  /// triple point or two more; room for two is kept. A cell of more (only in such a degenerate
  /// cluster, from 6 or 7 planes: 5 have at most C(5, 3) = 10 triple points) is `overflowed`,
  /// its vertices and faces incomplete, and its users reject it.
  static constexpr size_t kMaxVertices = 2 * kMaxPlanes - 4 + 2;
  using Face = FixedVector<int8_t, kMaxVertices>;  ///< indices into vertices, in cyclic order

  // User-provided, so that an array of cells (one per triangle) is not zero-filled first: only
  // the counts are set.
  ConvexCell() {}

  FixedVector<Vec4, kMaxPlanes> planes;
  FixedVector<Vec3, kMaxVertices> vertices;
  FixedVector<Face, kMaxPlanes> faces;  ///< one per plane
  double tolerance = 0.0;               ///< distance within which a point counts as on a plane
  bool overflowed = false;  ///< more than kMaxVertices distinct vertices: incomplete, unusable

  bool empty() const { return vertices.empty(); }
  /// Inside every plane, to within the tolerance.
  bool contains(const Vec3& p) const;
  Bounds3 bounds() const;
};

/// Vertices (triple intersections of the planes inside all of them) and faces. `tolerance` is
/// an absolute length (a small multiple of the round-off of the cell's size). At most
/// ConvexCell::kMaxPlanes planes (a logic error otherwise).
ConvexCell makeConvexCell(std::span<const Vec4> planes, double tolerance);

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
