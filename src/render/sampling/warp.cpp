#include "quadtri/render/sampling/warp.h"

#include <cmath>

#include "quadtri/render/sampling/frame.h"

namespace quadtri {
namespace {

/// Uniform in the cone cos θ ≥ 1 − h around +z, given h = 1 − cos θmax directly: small cones
/// (distant sphere lights) then keep full precision, as 1 − cos θ never cancels.
Vec3 coneFromOneMinusCos(const Vec2& u, double oneMinusCosMax) {
  const double h = u.x() * oneMinusCosMax;  // 1 − cos θ
  const double cosTheta = 1.0 - h;
  const double sinTheta = std::sqrt(std::max(0.0, h * (2.0 - h)));
  const double phi = 2.0 * kPi * u.y();
  return Vec3(sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta);
}

}  // namespace

double squareToUniformDiskConcentricPdf(const Vec2& p) {
  return p.squaredNorm() <= 1.0 ? kInvPi : 0.0;
}

Vec2 squareToUniformTriangle(const Vec2& u) {
  const double s = std::sqrt(u.x());
  return Vec2(1.0 - s, u.y() * s);
}

double squareToUniformTrianglePdf(const Vec2& b) {
  return (b.x() >= 0.0 && b.y() >= 0.0 && b.x() + b.y() <= 1.0) ? 2.0 : 0.0;
}

Vec3 squareToUniformSphere(const Vec2& u) {
  const double z = 1.0 - 2.0 * u.x();
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  const double phi = 2.0 * kPi * u.y();
  return Vec3(r * std::cos(phi), r * std::sin(phi), z);
}

double squareToUniformSpherePdf(const Vec3&) {
  return 0.25 * kInvPi;
}

Vec3 squareToUniformHemisphere(const Vec2& u) {
  const double z = u.x();
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  const double phi = 2.0 * kPi * u.y();
  return Vec3(r * std::cos(phi), r * std::sin(phi), z);
}

double squareToUniformHemispherePdf(const Vec3& v) {
  return v.z() >= 0.0 ? 0.5 * kInvPi : 0.0;
}

Vec3 squareToUniformCone(const Vec2& u, double cosThetaMax) {
  return coneFromOneMinusCos(u, 1.0 - cosThetaMax);
}

double squareToUniformConePdf(const Vec3& v, double cosThetaMax) {
  return v.z() >= cosThetaMax ? 1.0 / (2.0 * kPi * (1.0 - cosThetaMax)) : 0.0;
}

SphereDirectionSample sampleSphereCap(const Vec3& origin, const Vec3& center, double radius,
                                      const Vec2& u) {
  const Vec3 toCenter = center - origin;
  const double d2 = toCenter.squaredNorm();
  const double r2 = radius * radius;
  SphereDirectionSample out;
  if (d2 <= r2) {
    // Inside: every direction leaves through the sphere; the distance is the far root of
    // |o + t·ω − c|² = r², t = b + √(b² − (d² − r²)) with b = ω·(c − o).
    out.direction = squareToUniformSphere(u);
    const double b = out.direction.dot(toCenter);
    out.distance = b + std::sqrt(std::max(0.0, b * b - (d2 - r2)));
    out.pdf = 0.25 * kInvPi;
    return out;
  }
  const double d = std::sqrt(d2);
  const double sin2Max = r2 / d2;
  const double cosMax = std::sqrt(std::max(0.0, 1.0 - sin2Max));
  // 1 − cos θmax = sin²θmax / (1 + cos θmax) avoids the cancellation for distant spheres.
  const double oneMinusCosMax = sin2Max / (1.0 + cosMax);
  const Vec3 local = coneFromOneMinusCos(u, oneMinusCosMax);
  out.direction = Frame(toCenter / d).toWorld(local);
  // Near root of the ray–sphere quadratic, b − √(r² − d² sin²θ) with b = d cos θ; the radicand
  // is clamped because θ = θmax (tangent rays) makes it zero up to rounding.
  const double sin2 = local.x() * local.x() + local.y() * local.y();
  out.distance = d * local.z() - std::sqrt(std::max(0.0, r2 - d2 * sin2));
  out.pdf = 1.0 / (2.0 * kPi * oneMinusCosMax);
  return out;
}

double sphereCapPdf(const Vec3& origin, const Vec3& center, double radius, const Vec3& direction) {
  const Vec3 toCenter = center - origin;
  const double d2 = toCenter.squaredNorm();
  const double r2 = radius * radius;
  if (d2 <= r2) return 0.25 * kInvPi;
  const double d = std::sqrt(d2);
  const double sin2Max = r2 / d2;
  const double cosMax = std::sqrt(std::max(0.0, 1.0 - sin2Max));
  if (direction.dot(toCenter) < cosMax * d) return 0.0;
  return (1.0 + cosMax) / (2.0 * kPi * sin2Max);
}

double powerHeuristic(int nf, double fPdf, int ng, double gPdf) {
  const double f = nf * fPdf, g = ng * gPdf;
  if (!(f > 0.0)) return 0.0;
  if (std::isinf(f)) return 1.0;  // a Dirac strategy against a finite one takes all the weight
  // 1 / (1 + (g/f)²) is the same weight without overflowing f² for huge densities.
  const double ratio = g / f;
  return 1.0 / (1.0 + ratio * ratio);
}

}  // namespace quadtri
