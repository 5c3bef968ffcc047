// An implicit quadric clipped by planes: the render primitive of the implicit models.
#pragma once

#include <array>

#include "math/vec.h"

namespace quadtri {

/// Coefficients A..J of A x² + B y² + C z² + D xy + E xz + F yz + G x + H y + I z + J = 0.
using QuadricCoeffs = std::array<double, 10>;

double evalQuadric(const QuadricCoeffs& q, const Vec3& p);
Vec3 quadricGradient(const QuadricCoeffs& q, const Vec3& p);

/// A patch of the quadric q = 0 kept where every clip plane's (n·x + d) is >= 0, inside
/// `bounds`. `orientation` (+1 or -1) turns the gradient into the normal on the side of the
/// mesh's shading normals.
struct QuadricPatch {
  static constexpr int kMaxPlanes = 6;
  QuadricCoeffs q{};
  /// (n, d) with inside n·x + d >= 0 (Eigen leaves `{}` uninitialised: zero them explicitly).
  std::array<Vec4, kMaxPlanes> planes = [] {
    std::array<Vec4, kMaxPlanes> zero;
    zero.fill(Vec4::Zero());
    return zero;
  }();
  int planeCount = 0;
  Bounds3 bounds;
  double orientation = 1.0;

  bool inside(const Vec3& p) const {
    for (int i = 0; i < planeCount; ++i)
      if (planes[i].head<3>().dot(p) + planes[i][3] < 0.0) return false;
    return true;
  }
};

/// Nearest hit of the ray o + t d with the clipped patch for t in (tmin, tmax); the roots of the
/// quadratic are computed stably in double precision and each is tested against the planes
/// and the bounds. Returns false when there is none.
bool intersectQuadricPatch(const QuadricPatch& patch, const Vec3& o, const Vec3& d, double tmin,
                           double tmax, double& tHit);

}  // namespace quadtri
