// A quartic triangular Bézier piece: the render and analysis primitive of `quadric-g1`, traced
// directly (docs/DESIGN.md §13).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "quadtri/math/vec.h"

namespace quadtri {

/// b(λ) = Σ_{i+j+k=4} 4!/(i!j!k!) λ0^i λ1^j λ2^k b_ijk over barycentric λ = (1−u−v, u, v): (u, v) =
/// (0, 0) is corner 0, (1, 0) corner 1, (0, 1) corner 2.
struct BezierTriangle {
  static constexpr int kDegree = 4;
  static constexpr int kPoints = 15;
  /// Position of b_ijk (i = 4 − j − k) in `b`: rows of constant k, j increasing along a row.
  static constexpr int index(int j, int k) { return 5 * k - k * (k - 1) / 2 + j; }

  std::array<Vec3, kPoints> b;
  /// +1 or −1: the sign that turns ∂b/∂u × ∂b/∂v into the normal on the side of the mesh's
  /// shading normals.
  double orientation = 1.0;
  /// The mesh triangle the piece belongs to, and which of its pieces it is.
  uint32_t triangle = 0;
  uint8_t piece = 0;

  const Vec3& at(int i, int j, int k) const { return b[index(j, k)]; }
  Vec3& at(int i, int j, int k) { return b[index(j, k)]; }

  Vec3 position(double u, double v) const;
  /// ∂b/∂u and ∂b/∂v.
  void derivatives(double u, double v, Vec3& du, Vec3& dv) const;
  /// orientation · (∂b/∂u × ∂b/∂v), normalised; zero where the cross product vanishes.
  Vec3 normal(double u, double v) const;
  /// The position and the normal (as normal()) together, from one pass over the net.
  void positionAndNormal(double u, double v, Vec3& p, Vec3& n) const;
  /// Box of the control points (the piece lies in their convex hull), computed when asked: a
  /// stored box made every piece 48 bytes larger (144 MB at a million triangles).
  Bounds3 bounds() const;
  /// True where the piece is its corner triangle, parametrised linearly: every control point
  /// b_ijk lies within `relative` times the box's diagonal of (i·b_400 + j·b_040 + k·b_004)/4.
  /// Then b(u, v) is the triangle (b_400, b_040, b_004) at barycentric coordinates (u, v).
  bool isAffine(double relative) const;
};

}  // namespace quadtri
