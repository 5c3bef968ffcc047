// The local shading frame: BSDFs work in coordinates where the normal is +z, so their formulas
// read cos θ = z and never depend on how the surface is oriented in the world.
#pragma once

#include "quadtri/math/vec.h"

namespace quadtri {

/// Orthonormal frame (s, t, n): toLocal(v) = (v·s, v·t, v·n) and toWorld its transpose.
struct Frame {
  Vec3 s, t, n;

  /// The frame around unit normal `normal`, tangents from orthonormalBasis (Duff et al. 2017).
  explicit Frame(const Vec3& normal) : n(normal) { orthonormalBasis(n, s, t); }

  /// World -> local coordinates.
  Vec3 toLocal(const Vec3& v) const { return Vec3(v.dot(s), v.dot(t), v.dot(n)); }
  /// Local -> world coordinates.
  Vec3 toWorld(const Vec3& v) const { return s * v.x() + t * v.y() + n * v.z(); }
};

/// Mirror reflection of w about the unit vector m: 2(w·m)m − w.
inline Vec3 reflect(const Vec3& w, const Vec3& m) {
  return 2.0 * w.dot(m) * m - w;
}

/// Mirror reflection about the local normal +z: (−x, −y, z).
inline Vec3 reflectLocal(const Vec3& w) {
  return Vec3(-w.x(), -w.y(), w.z());
}

}  // namespace quadtri
