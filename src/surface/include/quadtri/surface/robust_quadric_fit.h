// The corner-exact quadric fit of `quadric-implicit-robust` (docs/DESIGN.md §3, findings on §4.3).
#pragma once

#include <array>

#include "quadtri/math/vec.h"
#include "quadtri/surface/quadric_patch.h"

namespace quadtri {

/// Midpoint of the circular arc that joins vi and vj inside the edge plane P_ij (through vi and
/// vj, spanned by vj-vi and ni+nj) and meets the chord at the mean of the angles the two tangent
/// planes make with it: m + (|e|/2)·tan(θ/2)·d, d the unit direction of P_ij perpendicular to
/// the chord on the normals' side. For data sampled from a sphere P_ij holds the centre, the arc
/// is a great circle and its midpoint lies on the sphere. Symmetric in (i, j); θ is clamped to
/// ±90° so inconsistent normals cannot fling the point away.
Vec3 edgeArcMidpoint(const Vec3& vi, const Vec3& ni, const Vec3& vj, const Vec3& nj);

/// The data a patch's quadric is fitted to: the corners, their shading normals and one arc
/// midpoint per edge (edge k joins corners k and k+1).
struct CornerData {
  std::array<Vec3, 3> position;
  std::array<Vec3, 3> normal;
  std::array<Vec3, 3> arcMidpoint;
};

/// Result of fitQuadric: q has unit coefficient norm and its gradient at the corners points to
/// the normals' side (Σ n_k·∇q(v_k) > 0).
struct QuadricFit {
  QuadricCoeffs q{};
  /// Largest angle (degrees) between ∇q at a corner and that corner's normal: 0 up to round-off
  /// when the data come from any quadric, O(h²) otherwise (see fitQuadric).
  double cornerNormalErrorDeg = 0.0;
  /// The direction q may move in without changing (1) and (2): the square of the triangle's
  /// plane (zero at a point triangle), on the same scale as q.
  QuadricCoeffs pencil{};
  /// True when the triangle has no extent or the hard rows (1) vanish or contradict each other:
  /// q is then the plane through the first corner with the mean normal, which gives up the
  /// other corners and the normals.
  bool pointFallback = false;
};

/// Fits q = 0 through the three corners exactly, in a local frame (origin at the centroid, unit
/// mean edge length, coefficients weighted so their norm is rotation invariant) so the result is
/// independent of the triangle's position and scale.
///
/// 1. Hard: q(v_k) = 0 and Σ_k n_k·∇q(v_k) = 1 (fixes scale and orientation, excludes the
///    gradient-free solutions).
/// 2. Tangency: minimise Σ_k |∇q(v_k) − (n_k·∇q(v_k)) n_k|² over what (1) leaves, damped toward
///    the smallest coefficients. Should that leave a corner's gradient (nearly) against its
///    normal (normals that no quadric comes near), (1) is replaced by n_k·∇q(v_k) = 1/3 at
///    every corner and (2) solved again. A quadric through three points with three prescribed
///    tangent planes exists only when a compatibility condition holds (its section by the
///    triangle's plane L is a conic through three points with three prescribed tangents: 6
///    conditions on 5 degrees of freedom). Data sampled from any quadric satisfy it and the minimum
///    is 0; generic data do not, and the minimum is the least corner-normal error.
/// 3. (2) is blind to L² (it vanishes with its gradient on the triangle's plane): the member
///    q + λL² is chosen by least squares through the three arc midpoints, exact for a sphere.
///    Flat data leave (2) and (3) underdetermined; the damping then returns the plane itself.
QuadricFit fitQuadric(const CornerData& data);

}  // namespace quadtri
