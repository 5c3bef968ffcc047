// Ray intersection of quartic Bézier triangles, traced directly (no tessellation).
//
// Method. The 15 control points are projected into the ray's frame: two unit vectors s, t
// perpendicular to d give (x, y) = ((b − o)·s, (b − o)·t), and z = (b − o)·d / |d|² is the ray
// parameter of the point's foot on the line. The ray hits the piece at (u, v) exactly where
// (x, y)(u, v) = (0, 0), and then t = z(u, v). By the convex-hull property a (sub-)net whose
// 2D box excludes the origin, or whose z range lies outside (tmin, tmax) (or beyond the nearest
// hit found so far), holds no hit and is culled; so is one whose mean-value enclosure
// F(centre) + [∂F/∂u]·Δu + [∂F/∂v]·Δv excludes it. Surviving nets are bisected (newest-vertex
// bisection: the edge opposite corner 0 at its midpoint, by one chain of de Casteljau steps that
// gives both halves; two bisections make a midpoint 4-split), depth first, nearer half first,
// on a fixed-size stack (no heap allocation).
//
// A net is solved once it is known to hold at most one hit: when every 2D cross product of a
// control vector of ∂(x, y)/∂u with one of ∂(x, y)/∂v has the same sign, the average Jacobian
// between any two points of the sub-triangle is non-singular, so (x, y) is injective on it.
// Newton then runs on the 2D system of the WHOLE piece, from where the ray crosses the
// sub-triangle's planar corner triangle; a root is accepted when it lies in the sub-triangle
// (up to 1e-6 of its size) and in the piece's domain up to 1e-9, so a ray through the boundary
// two pieces share is found by both (hits from neighbouring sub-triangles are merged by (u, v)).
// When Newton does not converge there, or converges outside (then the halves skip it), or the
// net may fold, bisection goes on; at the maximum depth (30 bisections: 1/32768 of the piece's
// size) Newton is tried anyway, from the corners too where the net may fold, and should it
// still fail, the planar corner triangle stands in, so no hit is lost. A budget of nodes bounds
// the work on degenerate pieces.
#pragma once

#include <vector>

#include "quadtri/math/vec.h"
#include "quadtri/surface/bezier_triangle.h"

namespace quadtri {

/// A ray's hit on a Bézier piece: the ray parameter and the piece's (u, v).
struct BezierHit {
  double t = kInfinity;
  double u = 0.0, v = 0.0;
};

/// Nearest hit of o + t·d (d need not be unit) with the piece for t in (tmin, tmax). Returns
/// false, leaving `hit` untouched, when there is none.
bool intersectBezierTriangle(const BezierTriangle& piece, const Vec3& o, const Vec3& d, double tmin,
                             double tmax, BezierHit& hit);

/// True when the ray hits the piece anywhere in (tmin, tmax) (stops at the first hit found).
bool occludesBezierTriangle(const BezierTriangle& piece, const Vec3& o, const Vec3& d, double tmin,
                            double tmax);

/// Appends every hit in (tmin, tmax) to `hits`, unordered and each once; returns how many.
size_t intersectBezierTriangleAll(const BezierTriangle& piece, const Vec3& o, const Vec3& d,
                                  double tmin, double tmax, std::vector<BezierHit>& hits);

/// The piece's 4 midpoint sub-triangles, each over a quarter of its domain: 0 at corner 0
/// ((0,0), (½,0), (0,½)), 1 at corner 1 ((½,0), (1,0), (½,½)), 2 at corner 2 ((0,½), (½,½),
/// (0,1)) and 3 in the middle ((½,½), (0,½), (½,0)), all with the piece's orientation, triangle
/// and piece ids, and bounds. Sub-triangle m at its (u', v') is the piece at
/// c0 + u'(c1 − c0) + v'(c2 − c0) for its corners c0, c1, c2 above.
std::array<BezierTriangle, 4> subdivideBezierTriangle(const BezierTriangle& piece);

}  // namespace quadtri
