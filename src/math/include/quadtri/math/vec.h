// Geometry types: double precision throughout conversion and analysis; Embree takes floats.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace quadtri {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Vec4 = Eigen::Vector4d;
using Mat3 = Eigen::Matrix3d;
using Mat4 = Eigen::Matrix4d;

constexpr double kPi = 3.14159265358979323846;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// v/|v|, or `fallback` when |v| is zero or not finite (never returns NaN); |v| goes to `length`
/// (one square root for both).
inline Vec3 safeNormalized(const Vec3& v, double& length, const Vec3& fallback = Vec3(0, 0, 1)) {
  length = v.norm();
  if (!(length > 0.0) || !std::isfinite(length)) return fallback;
  return v / length;
}
/// The same without the length.
inline Vec3 safeNormalized(const Vec3& v, const Vec3& fallback = Vec3(0, 0, 1)) {
  double length;
  return safeNormalized(v, length, fallback);
}

/// Angle between two vectors in degrees, robust near 0 and 180 (atan2 of |a×b| and a·b).
inline double angleDegrees(const Vec3& a, const Vec3& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * (180.0 / kPi);
}

inline bool allFinite(const Vec3& v) {
  return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z());
}

/// Axis-aligned bounding box; empty until a point is added.
struct Bounds3 {
  Vec3 lo = Vec3::Constant(kInfinity);
  Vec3 hi = Vec3::Constant(-kInfinity);

  void extend(const Vec3& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  void extend(const Bounds3& b) {
    lo = lo.cwiseMin(b.lo);
    hi = hi.cwiseMax(b.hi);
  }
  bool empty() const { return !(lo.x() <= hi.x()); }
  Vec3 diagonal() const { return empty() ? Vec3::Zero() : Vec3(hi - lo); }
  Vec3 center() const { return 0.5 * (lo + hi); }
  /// The area of the box's six faces (0 when empty): what the chance that a ray meets it is
  /// proportional to.
  double surfaceArea() const {
    const Vec3 d = diagonal();
    return 2.0 * (d.x() * d.y() + d.y() * d.z() + d.z() * d.x());
  }
  /// p inside the box or on its faces.
  bool contains(const Vec3& p) const {
    return (p.array() >= lo.array()).all() && (p.array() <= hi.array()).all();
  }
  /// Grows the box by `margin` on every side.
  void inflate(double margin) {
    lo.array() -= margin;
    hi.array() += margin;
  }
};

/// Builds an orthonormal basis (s, t, n) around unit n (Duff et al. 2017, branchless).
inline void orthonormalBasis(const Vec3& n, Vec3& s, Vec3& t) {
  const double sign = std::copysign(1.0, n.z());
  const double a = -1.0 / (sign + n.z());
  const double b = n.x() * n.y() * a;
  s = Vec3(1.0 + sign * n.x() * n.x() * a, sign * b, -sign * n.x());
  t = Vec3(b, sign + n.y() * n.y() * a, -n.y());
}

}  // namespace quadtri
