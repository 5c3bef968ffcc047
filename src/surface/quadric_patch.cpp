#include "quadtri/surface/quadric_patch.h"

#include <cmath>

namespace quadtri {

QuadricCoeffs translatedQuadric(const QuadricCoeffs& q, const Vec3& o) {
  const Mat3 M = quadraticPart(q);
  const Vec3 g(q[6], q[7], q[8]);
  const Vec3 linear = g - 2.0 * (M * o);
  QuadricCoeffs out = q;
  out[6] = linear.x();
  out[7] = linear.y();
  out[8] = linear.z();
  out[9] = q[9] + (o.dot(M * o) - g.dot(o));
  return out;
}

Mat3 quadraticPart(const QuadricCoeffs& q) {
  Mat3 m;
  m << q[0], 0.5 * q[3], 0.5 * q[4], 0.5 * q[3], q[1], 0.5 * q[5], 0.5 * q[4], 0.5 * q[5], q[2];
  return m;
}

namespace {

// The roots of the patch's quadric along o + t d in (tmin, tmax), nearest first, that lie inside
// the planes and bounds and pass `accept`.
template <typename Accept>
bool nearestRoot(const QuadricPatch& patch, const Vec3& o, const Vec3& d, double tmin, double tmax,
                 double& tHit, const Accept& accept) {
  const QuadricCoeffs& q = patch.q;
  const double a = q[0] * d.x() * d.x() + q[1] * d.y() * d.y() + q[2] * d.z() * d.z() +
                   q[3] * d.x() * d.y() + q[4] * d.x() * d.z() + q[5] * d.y() * d.z();
  const double b = quadricGradient(q, o).dot(d);
  const double c = evalQuadric(q, o);
  double roots[2];
  int count = 0;
  const double scale = std::abs(b) + std::abs(c) * 1e-300;
  if (std::abs(a) <= 1e-14 * scale) {
    if (b == 0.0) return false;
    roots[count++] = -c / b;
  } else {
    const double disc = b * b - 4.0 * a * c;
    if (disc < 0.0) return false;
    const double s = std::sqrt(disc);
    const double h = -0.5 * (b + std::copysign(s, b));
    if (h == 0.0) {
      roots[count++] = 0.0;
    } else {
      roots[count++] = h / a;
      roots[count++] = c / h;
    }
    if (count == 2 && roots[0] > roots[1]) std::swap(roots[0], roots[1]);
  }
  for (int i = 0; i < count; ++i) {
    const double t = roots[i];
    if (!(t > tmin && t < tmax)) continue;
    const Vec3 p = o + t * d;
    // The box first: the cheapest test, and next to q in the record.
    if ((p.array() < patch.bounds.lo.array()).any() || (p.array() > patch.bounds.hi.array()).any())
      continue;
    if (!patch.inside(p)) continue;
    if (!accept(p)) continue;
    tHit = t;
    return true;
  }
  return false;
}

}  // namespace

bool intersectQuadricPatch(const QuadricPatch& patch, const Vec3& o, const Vec3& d, double tmin,
                           double tmax, double& tHit) {
  return nearestRoot(patch, o, d, tmin, tmax, tHit, [](const Vec3&) { return true; });
}

bool insideQuadric(const QuadricPatch& patch, const Vec3& p) {
  return patch.orientation * evalQuadric(patch.q, p) < 0.0;
}

bool betweenSheetAndBase(const QuadricPatch& patch, const Vec3& p, int skipPlane) {
  if (patch.base == Vec4::Zero()) return false;
  for (int i = 0; i < patch.planeCount; ++i)
    if (i != skipPlane && patch.planes[i].head<3>().dot(p) + patch.planes[i][3] < 0.0) return false;
  const bool insideSheet = patch.orientation * evalQuadric(patch.q, p) < 0.0;
  const bool belowBase = patch.base.head<3>().dot(p) + patch.base[3] < 0.0;
  return insideSheet != belowBase;
}

bool bridgeCovers(const std::vector<QuadricPatch>& primitives, const QuadricPatch& bridge,
                  const Vec3& p) {
  const QuadricPatch& a = primitives[size_t(bridge.joins[0])];
  const QuadricPatch& b = primitives[size_t(bridge.joins[1])];
  if (bridge.joinPlanes[0] >= 0)
    return betweenSheetAndBase(a, p, bridge.joinPlanes[0]) !=
           betweenSheetAndBase(b, p, bridge.joinPlanes[1]);
  return insideQuadric(a, p) != insideQuadric(b, p);
}

namespace {

// For a bridge: whether the solid lies on its first patch's side at p.
bool solidOnFirstSide(const std::vector<QuadricPatch>& primitives, const QuadricPatch& bridge,
                      const Vec3& p) {
  const QuadricPatch& a = primitives[size_t(bridge.joins[0])];
  if (bridge.joinPlanes[0] < 0) return insideQuadric(a, p);
  // Near its triangle the flat solid is below the base; the region between sheet and base
  // flips that.
  const bool belowBase = a.base.head<3>().dot(p) + a.base[3] < 0.0;
  return belowBase != betweenSheetAndBase(a, p, bridge.joinPlanes[0]);
}

}  // namespace

bool intersectPrimitive(const std::vector<QuadricPatch>& primitives, size_t index, const Vec3& o,
                        const Vec3& d, double tmin, double tmax, double& tHit) {
  const QuadricPatch& patch = primitives[index];
  if (!patch.isBridge()) return intersectQuadricPatch(patch, o, d, tmin, tmax, tHit);
  return nearestRoot(patch, o, d, tmin, tmax, tHit,
                     [&](const Vec3& p) { return bridgeCovers(primitives, patch, p); });
}

bool intersectPrimitiveWithin(const std::vector<QuadricPatch>& primitives, size_t index,
                              const Bounds3& within, const Vec3& o, const Vec3& d, double tmin,
                              double tmax, double& tHit) {
  const QuadricPatch& patch = primitives[index];
  const auto inside = [&](const Vec3& p) {
    return (p.array() >= within.lo.array()).all() && (p.array() <= within.hi.array()).all();
  };
  if (!patch.isBridge()) return nearestRoot(patch, o, d, tmin, tmax, tHit, inside);
  return nearestRoot(patch, o, d, tmin, tmax, tHit, [&](const Vec3& p) {
    return inside(p) && bridgeCovers(primitives, patch, p);
  });
}

Vec3 primitiveNormal(const std::vector<QuadricPatch>& primitives, size_t index, const Vec3& p) {
  const QuadricPatch& patch = primitives[index];
  const Vec3 g = patch.orientation * quadricGradient(patch.q, p);
  if (!patch.isBridge()) return safeNormalized(g, Vec3::Zero());
  // The plane's gradient points into the first patch's side: the solid lies on that side where
  // p is inside the first patch's quadric.
  return safeNormalized(solidOnFirstSide(primitives, patch, p) ? Vec3(-g) : g, Vec3::Zero());
}

Vec3 primitiveShadingNormal(const std::vector<QuadricPatch>& primitives, size_t index,
                            const Vec3& p) {
  const QuadricPatch& patch = primitives[index];
  if (!patch.isBridge()) return primitiveNormal(primitives, index, p);
  Vec3 sum = Vec3::Zero();
  for (int32_t side : patch.joins) sum += primitiveNormal(primitives, size_t(side), p);
  return safeNormalized(sum, primitiveNormal(primitives, index, p));
}

}  // namespace quadtri
