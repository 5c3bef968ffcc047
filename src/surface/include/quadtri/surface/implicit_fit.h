// The thesis' implicit quadric triangle (§4.3): least-squares implicitisation of a parametric
// quadric triangle, the four clip planes, and projection onto the quadric along a ray.
#pragma once

#include <optional>

#include "quadtri/surface/edge_curves.h"
#include "quadtri/surface/quadric_patch.h"

namespace quadtri {

/// Coefficients A..J of the quadric f_i fitted to the parametric patch f_p by the thesis'
/// least squares, rows exactly as printed, in world coordinates:
///   eq. 4.10  f_i(f_p(c)) = 0                            at the corners c = (0,0), (1,0), (0,1)
///   eq. 4.11  ∇f_i(f_p(c))·∂f_p/∂u(c) = ∇f_i(f_p(c))·∂f_p/∂v(c) = 0   at the same corners
///   eq. 4.12  the value row and both tangency rows at the barycentre (1/3, 1/3)
///   eq. 4.13  A + B + … + J = 1
/// The thesis counts "12 equations" but its printed rows are 3 + 6 + 3 + 1 = 13; all 13 are used.
/// The minimum-norm least-squares solution is taken (SVD), so rank-deficient systems (a
/// degenerate triangle) still give one finite answer.
///
/// A planar patch (every edge control point in the plane of the corners, e.g. all normals equal
/// to the face normal) makes every homogeneous row vanish on the whole family L·M (L the
/// triangle's plane, M any affine function), whose zero set is the triangle's plane plus a
/// spurious second plane M = 0. Among these exact solutions the plane L itself is returned,
/// scaled so that eq. 4.13 holds (or to a unit normal where its coefficients sum to ~0).
///
/// The row A+…+J = 1 is not scale-free: scaling the mesh by s scales the monomial columns by
/// s², s and 1 but not that row, so where the other rows conflict (any generic mesh) the
/// fitted shape, not just its size, depends on the mesh's units: on the built-in ellipsoid the
/// coefficient vectors fitted in units 1 and 1e3 differ by up to 75°. Where the 12 homogeneous
/// rows have an exact one-dimensional solution (the regular icosahedron, by symmetry) the row
/// only sets the scale and the fit is scale-covariant. This is the thesis' method and is kept.
QuadricCoeffs fitThesisQuadric(const QuadraticPatch& fp);

/// Fills patch.planes/planeCount with the thesis' four clip planes, each through three points
/// of f_p: (1) f_p(0,0), f_p(1,0), f_p(0,1); (2) f_p(0,0), f_p(½,0), f_p(1,0); (3) f_p(0,0),
/// f_p(0,½), f_p(0,1); (4) f_p(1,0), f_p(½,½), f_p(1,1) (the thesis prints "f_p(0, 0, 5)" for
/// the middle points, and its f_p(1,1) lies outside the triangle's domain). Each normal
/// n = (p2-p1)×(p3-p1) is unit-scaled and flipped to point to the barycentre f_p(⅓,⅓); points
/// with n·(x - p1) >= 0 are kept, i.e. the barycentre's side.
///
/// Degenerate planes: when the three points are collinear (a straight edge makes plane 2 or 3
/// collinear) or the barycentre lies on the plane (a planar patch: plane 1 is the patch's own
/// plane and plane 4 contains it), planes 2-4 are replaced by the plane through their edge's
/// chord that contains the triangle's normal, and plane 1 is dropped. A plane that is still
/// undefined (zero-area triangle) is dropped. No plane has a NaN.
///
/// Measured on the icosahedron: plane 4 does not follow edge 1 (corners 1-2); it trims the
/// patch up to λ0 = 0.1 inside that edge and keeps a sliver of the quadric beyond it, which
/// only the patch's bounding box (implicit_model.h) cuts off.
void setThesisClipPlanes(const QuadraticPatch& fp, QuadricPatch& patch);

/// The real roots of a s² + b s + c along a line (a linear equation where a is 0), computed
/// without cancellation; returns how many were written to `roots` (0 to 2, unordered).
int lineQuadricRoots(double a, double b, double c, double roots[2]);

/// The root s of q(p + s·d) = 0 with the smallest |s| (the quadratic in s solved in closed form
/// with the cancellation-free formula), or nullopt when there is no real root with
/// |s|·|d| <= maxDistance.
std::optional<double> nearestRayRoot(const QuadricCoeffs& q, const Vec3& p, const Vec3& d,
                                     double maxDistance);

}  // namespace quadtri
