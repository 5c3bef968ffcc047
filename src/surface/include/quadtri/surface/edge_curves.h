// Quadratic edge curves shared by neighbouring patches (thesis §4.1, eq. 4.4-4.5).
#pragma once

#include <array>
#include <vector>

#include "quadtri/mesh/topology.h"
#include "quadtri/mesh/triangle_mesh.h"

namespace quadtri {

/// The least-squares solution δ of [M; μI] δ = [r; 0] (Tikhonov: the minimiser of |Mδ − r|² +
/// μ²|δ|²), by a fixed-size Householder QR (math/least_squares.h); μ > 0.
Vec3 dampedLeastSquares(const Mat3& M, const Vec3& r, double mu);

/// True when the edge's ends (vi, ni) and (vj, nj) should be swapped into the canonical order
/// (lexicographic on positions, then normals), so a formula symmetric in the two ends gives
/// the same bits whichever side of the edge evaluates it.
bool edgeEndsSwapped(const Vec3& vi, const Vec3& ni, const Vec3& vj, const Vec3& nj);

/// Control point b of the quadratic Bézier edge (1-t)² vi + 2t(1-t) b + t² vj: the intersection
/// of the tangent plane at vi (normal ni), the tangent plane at vj (normal nj) and the thesis'
/// edge plane (eq. 4.5: through vi, normal (vj-vi)×(m+nm-vi)). This is the closed form of the
/// thesis' 27×27 (§4.1) and 18×18 (§4.2) systems, which decouple into one 3×3 system per edge.
///
/// The solve is symmetric in (i, j) bit for bit, so both patches of an edge get the same point.
/// Where the tangent planes are (nearly) parallel the system is singular: a damped
/// pseudo-inverse drives the offset from the chord midpoint smoothly to the straight edge, and
/// the offset is bounded by the edge length so inconsistent normals cannot fling it away.
/// `gaveUp`, when given, is set to whether the point gives up the tangent planes: the bound
/// replaced the solution, the solve was not finite (the chord midpoint is returned), or the
/// damped solve leaves the point off either tangent plane by more than 1e-6 of the edge length
/// (parallel planes that do not hold the edge, e.g. a step between equal normals).
Vec3 edgeControlPoint(const Vec3& vi, const Vec3& ni, const Vec3& vj, const Vec3& nj,
                      bool* gaveUp = nullptr);

/// Control points of every triangle's edges: result[t][k] belongs to local edge k (corners k
/// and (k+1)%3). Each mesh edge is solved once, from data both sides share (creases.h): where
/// its triangles carry the same normal at each end, edgeControlPoint of those normals; where
/// they split normals at an end by less than kCreaseMinDegrees, edgeControlPoint of the
/// normalised means; at a crease (normals split further), creaseControlPoint, whose tangent
/// there follows the crease line n₁ × n₂ (a cube's edges stay straight).
/// `gaveUpPatches`, when given, gets one flag per triangle: 1 where one of its edges' control
/// points gave up its tangent planes (see edgeControlPoint; the crease rule reports none).
std::vector<std::array<Vec3, 3>> edgeControlPoints(const TriangleMesh& mesh,
                                                   std::vector<uint8_t>* gaveUpPatches = nullptr);
/// The same on the mesh's adjacency built once by the caller.
std::vector<std::array<Vec3, 3>> edgeControlPoints(const TriangleMesh& mesh,
                                                   const MeshTopology& topo,
                                                   std::vector<uint8_t>* gaveUpPatches = nullptr);

/// True where edgeControlPoints needs no adjacency: the mesh has normals and no vertex's corners
/// carry different ones (creases.h, edgeEndsNeedTopology), so each edge's control point follows
/// from the corners and normals either of its triangles holds.
bool edgeControlPointsAreLocal(const TriangleMesh& mesh);
/// Triangle t's three edge control points on such a mesh, bit for bit what edgeControlPoints
/// gives it (edgeControlPoint orders an edge's ends canonically, so both sides compute the same
/// point); `gaveUp`, when given, is set to whether one of them gave up its tangent planes.
std::array<Vec3, 3> localEdgeControlPoints(const TriangleMesh& mesh, size_t t,
                                           bool* gaveUp = nullptr);

/// The quadratic Bézier triangle with corners v[k] and edge control points b[k] (edge k joins
/// corners k and k+1), in barycentric (u, v) with corner 0 at (0,0), 1 at (1,0), 2 at (0,1).
/// This is the thesis' §4.2 parametric quadric triangle
/// f(u,v) = u² c5 + v² c4 + uv c3 + u c2 + v c1 + c0.
struct QuadraticPatch {
  std::array<Vec3, 3> v;
  std::array<Vec3, 3> b;

  /// The thesis' coefficients c0..c5 (eq. 4.6).
  std::array<Vec3, 6> coefficients() const;
  Vec3 position(double u, double w) const;
  /// ∂f/∂u and ∂f/∂v at (u, v).
  void derivatives(double u, double w, Vec3& du, Vec3& dv) const;
  /// Point on edge k at parameter t from corner k to corner k+1.
  Vec3 edgePoint(int k, double t) const;
};

// Inline: conversion evaluates them at dozens of points per patch.
inline Vec3 QuadraticPatch::position(double u, double w) const {
  const double l0 = 1.0 - u - w, l1 = u, l2 = w;
  return l0 * l0 * v[0] + l1 * l1 * v[1] + l2 * l2 * v[2] + 2.0 * l0 * l1 * b[0] +
         2.0 * l1 * l2 * b[1] + 2.0 * l2 * l0 * b[2];
}

inline void QuadraticPatch::derivatives(double u, double w, Vec3& du, Vec3& dv) const {
  const double l0 = 1.0 - u - w, l1 = u, l2 = w;
  // ∂/∂u moves weight from λ0 to λ1; ∂/∂v from λ0 to λ2.
  du = 2.0 * (l1 * v[1] - l0 * v[0] + (l0 - l1) * b[0] + l2 * b[1] - l2 * b[2]);
  dv = 2.0 * (l2 * v[2] - l0 * v[0] - l1 * b[0] + l1 * b[1] + (l0 - l2) * b[2]);
}

/// The patch of triangle t, with control points from `controlPoints` (edgeControlPoints).
QuadraticPatch quadraticPatch(const TriangleMesh& mesh,
                              const std::vector<std::array<Vec3, 3>>& controlPoints, size_t t);

/// +1 or -1: the sign that orients (p_u × p_v) of triangle t towards its shading normals.
double patchOrientation(const TriangleMesh& mesh, size_t t);

}  // namespace quadtri
