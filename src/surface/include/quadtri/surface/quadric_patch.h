// An implicit quadric clipped by planes: the render primitive of the implicit models.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "quadtri/math/vec.h"

namespace quadtri {

/// Coefficients A..J of A x² + B y² + C z² + D xy + E xz + F yz + G x + H y + I z + J = 0.
using QuadricCoeffs = std::array<double, 10>;

// Inline: conversion evaluates them dozens of times per patch, tracing on every candidate.
inline double evalQuadric(const QuadricCoeffs& q, const Vec3& p) {
  const double x = p.x(), y = p.y(), z = p.z();
  return q[0] * x * x + q[1] * y * y + q[2] * z * z + q[3] * x * y + q[4] * x * z + q[5] * y * z +
         q[6] * x + q[7] * y + q[8] * z + q[9];
}
inline Vec3 quadricGradient(const QuadricCoeffs& q, const Vec3& p) {
  const double x = p.x(), y = p.y(), z = p.z();
  return Vec3(2 * q[0] * x + q[3] * y + q[4] * z + q[6], 2 * q[1] * y + q[3] * x + q[5] * z + q[7],
              2 * q[2] * z + q[4] * x + q[5] * y + q[8]);
}
/// How far the zero set of q, as evaluated in double precision, may lie from the exact one at a
/// point p of it where |∇q| = gradientLength: 32 units of rounding (2⁻⁴⁸) of the sum of the
/// absolute values of q's terms at p, over the gradient's length. Far from the world origin
/// the terms are large and cancel, so this grows with |p|² where the patch's own size does not;
/// 0 where the gradient vanishes.
inline double quadricRootError(const QuadricCoeffs& q, const Vec3& p, double gradientLength) {
  if (!(gradientLength > 0.0)) return 0.0;
  const double x = std::abs(p.x()), y = std::abs(p.y()), z = std::abs(p.z());
  const double terms = std::abs(q[0]) * x * x + std::abs(q[1]) * y * y + std::abs(q[2]) * z * z +
                       std::abs(q[3]) * x * y + std::abs(q[4]) * x * z + std::abs(q[5]) * y * z +
                       std::abs(q[6]) * x + std::abs(q[7]) * y + std::abs(q[8]) * z +
                       std::abs(q[9]);
  return 0x1.0p-48 * terms / gradientLength;
}
/// q(x − o) as a quadric in x (q moved by o): the quadratic part is unchanged, the linear
/// part gains −2M·o and the constant oᵀMo − g·o.
QuadricCoeffs translatedQuadric(const QuadricCoeffs& q, const Vec3& o);
/// The symmetric M of q's quadratic part: A x² + ... + F yz = xᵀ M x.
Mat3 quadraticPart(const QuadricCoeffs& q);

/// A patch of the quadric q = 0 kept where every clip plane's (n·x + d) is >= 0, inside
/// `bounds`. `orientation` (+1 or -1) turns the gradient into the normal on the side of the
/// mesh's shading normals.
struct QuadricPatch {
  static constexpr int kMaxPlanes = 6;
  // The fields are in the order a ray test reads them, so that a test of an ordinary patch
  // touches one contiguous run of the record: which kind of primitive it is, the quadric, its
  // box, then as many planes as it has.

  /// For an edge bridge: the indices (in the same primitive array) of the two patches it joins;
  /// -1 for an ordinary patch. A bridge's q is the shared edge plane (linear, gradient into the
  /// first patch's side) and the bridge is the part of that plane, inside its clip planes and
  /// bounds, where the two patches disagree about inside and outside: the sliver between the
  /// conics in which their quadrics meet the plane. With it, neighbouring patches that do not
  /// meet exactly still bound a closed solid.
  std::array<int32_t, 2> joins{-1, -1};
  /// For a bridge between patches with a `base`: the plane of each joined patch (an index into
  /// its planes) that the bridge lies in; see bridgeCovers.
  std::array<int8_t, 2> joinPlanes{-1, -1};
  int16_t planeCount = 0;
  /// ±1: the sign that makes the gradient of q point out of the solid. A float, exact for ±1,
  /// so that it shares the header's 16 bytes (a double after the box cost the record 16 bytes
  /// of alignment before the planes, which are Vec4-aligned).
  float orientation = 1.0f;
  QuadricCoeffs q{};
  Bounds3 bounds;
  /// (n, d) with inside n·x + d >= 0 (Eigen leaves `{}` uninitialised: zero them explicitly).
  std::array<Vec4, kMaxPlanes> planes = [] {
    std::array<Vec4, kMaxPlanes> zero;
    zero.fill(Vec4::Zero());
    return zero;
  }();
  /// Where non-zero (n, d with unit n): the plane of the patch's triangle, n on the side the
  /// oriented gradient points to. The patch's planes then bound a convex cell whose section by
  /// this plane is the triangle, and the patch stands for the region of the cell between its
  /// quadric and this plane (see betweenSheetAndBase).
  Vec4 base = Vec4::Zero();

  bool isBridge() const { return joins[0] >= 0; }

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

/// True where p lies inside the solid that patch bounds: orientation·q(p) < 0 (the oriented
/// gradient points outward).
bool insideQuadric(const QuadricPatch& patch, const Vec3& p);

/// For a patch with a `base`: p lies in the patch's cell (every plane but `skipPlane`, which
/// may be -1) and between its quadric and its base plane, i.e. orientation·q(p) < 0 and
/// base(p) < 0 disagree. False for a patch without a base.
bool betweenSheetAndBase(const QuadricPatch& patch, const Vec3& p, int skipPlane);

/// True where the bridge `bridge` of `primitives` exists at p (a point of its plane). Between
/// patches with a base (`quadric-implicit-robust`): exactly one of the two is between its sheet
/// and its base at p (betweenSheetAndBase, the bridge's plane skipped). The solid is the flat
/// mesh's, changed by every cell's region between sheet and base; its boundary is every
/// patch's quadric inside its cell and, on each cell face, where that region meets the face:
/// on a face shared by two cells the two contributions cancel where they coincide, and what
/// remains is this bridge. That surface is closed whatever the quadrics are. Otherwise (legacy
/// bridges): the two patches disagree about p's side (insideQuadric).
bool bridgeCovers(const std::vector<QuadricPatch>& primitives, const QuadricPatch& bridge,
                  const Vec3& p);

/// intersectQuadricPatch for primitive `index` of `primitives`, bridges included.
bool intersectPrimitive(const std::vector<QuadricPatch>& primitives, size_t index, const Vec3& o,
                        const Vec3& d, double tmin, double tmax, double& tHit);

/// intersectPrimitive for a part of a primitive (quadric_patch_parts.h): its nearest root that
/// also lies in the closed box `within`.
bool intersectPrimitiveWithin(const std::vector<QuadricPatch>& primitives, size_t index,
                              const Bounds3& within, const Vec3& o, const Vec3& d, double tmin,
                              double tmax, double& tHit);

/// Unit outward normal of primitive `index` at p: the oriented gradient of a patch; for a bridge
/// its plane's normal, pointing from the side inside the solid to the side outside. Zero where
/// the gradient vanishes.
Vec3 primitiveNormal(const std::vector<QuadricPatch>& primitives, size_t index, const Vec3& p);

/// The normal to shade primitive `index` with at p: primitiveNormal for a patch; for a bridge
/// (a sliver across an edge) the normalised mean of the two joined patches' normals, so the
/// sliver shades like the surface around it.
Vec3 primitiveShadingNormal(const std::vector<QuadricPatch>& primitives, size_t index,
                            const Vec3& p);

}  // namespace quadtri
