// Warps from the unit square [0,1)² to the domains a path tracer samples, each paired with the
// density it produces (w.r.t. solid angle on the sphere, area in the plane), so that Monte Carlo
// estimators divide by exactly what was sampled. The pdf functions return zero off the domain.
#pragma once

#include "quadtri/math/vec.h"

namespace quadtri {

/// Concentric map (Shirley & Chiu 1997) to the unit disk: uniform, area-preserving, low distortion.
Vec2 squareToUniformDiskConcentric(const Vec2& u);
/// 1/π inside the unit disk.
double squareToUniformDiskConcentricPdf(const Vec2& p);

/// Uniform barycentrics (b0, b1) of a triangle: b0 = 1 − √u0, b1 = u1·√u0 (b2 = 1 − b0 − b1).
Vec2 squareToUniformTriangle(const Vec2& u);
/// 2 on the triangle b0, b1 ≥ 0, b0 + b1 ≤ 1 (the barycentric triangle has area 1/2).
double squareToUniformTrianglePdf(const Vec2& b);

/// Uniform on the unit sphere: z = 1 − 2u0, φ = 2πu1.
Vec3 squareToUniformSphere(const Vec2& u);
/// 1/(4π).
double squareToUniformSpherePdf(const Vec3& v);

/// Uniform on the upper unit hemisphere (z ≥ 0): z = u0, φ = 2πu1.
Vec3 squareToUniformHemisphere(const Vec2& u);
/// 1/(2π) for z ≥ 0.
double squareToUniformHemispherePdf(const Vec3& v);

/// Cosine-weighted upper hemisphere (Malley: lift the concentric disk sample to the sphere).
Vec3 squareToCosineHemisphere(const Vec2& u);
/// cos θ / π for z ≥ 0.
double squareToCosineHemispherePdf(const Vec3& v);

/// Uniform in the cone of directions around +z with cos θ ≥ cosThetaMax.
Vec3 squareToUniformCone(const Vec2& u, double cosThetaMax);
/// 1 / (2π(1 − cosThetaMax)) inside the cone.
double squareToUniformConePdf(const Vec3& v, double cosThetaMax);

/// A direction towards a sphere, the distance along it to the sphere (the near intersection from
/// outside, the only one ahead from inside), and its solid-angle pdf.
struct SphereDirectionSample {
  Vec3 direction;
  double distance = 0.0;
  double pdf = 0.0;
};

/// Uniform over the cone of directions from `origin` that hit the sphere (center, radius): the
/// solid angle the sphere subtends, 2π(1 − cos θmax) with sin θmax = r/d. From inside the sphere
/// every direction hits it, so the whole sphere of directions is sampled uniformly.
SphereDirectionSample sampleSphereCap(const Vec3& origin, const Vec3& center, double radius,
                                      const Vec2& u);
/// The solid-angle density of sampleSphereCap for the unit `direction` (zero outside the cone).
double sphereCapPdf(const Vec3& origin, const Vec3& center, double radius, const Vec3& direction);

/// Veach's power heuristic (β = 2) weight of strategy f: (nf·pf)² / ((nf·pf)² + (ng·pg)²).
double powerHeuristic(int nf, double fPdf, int ng, double gPdf);

}  // namespace quadtri
