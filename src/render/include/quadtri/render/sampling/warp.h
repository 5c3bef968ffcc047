// Warps from the unit square [0,1)² to the domains a path tracer samples, each paired with the
// density it produces (w.r.t. solid angle on the sphere, area in the plane), so that Monte Carlo
// estimators divide by exactly what was sampled. The pdf functions return zero off the domain.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "quadtri/math/vec.h"

namespace quadtri {

inline constexpr double kInvPi = 1.0 / kPi;

namespace warp_detail {
/// Taylor coefficients (−1)^m / (2m + first)! for m = 0 … N − 1.
template <int N>
constexpr std::array<double, N> alternatingInverseFactorials(int first) {
  std::array<double, N> c{};
  double factorial = 1.0;
  for (int k = 2; k <= first; ++k) factorial *= double(k);
  for (int m = 0; m < N; ++m) {
    c[size_t(m)] = (m % 2 == 0 ? 1.0 : -1.0) / factorial;
    factorial *= double(2 * m + first + 1) * double(2 * m + first + 2);
  }
  return c;
}
inline constexpr auto kSinSeries = alternatingInverseFactorials<9>(1);
inline constexpr auto kCosSeries = alternatingInverseFactorials<10>(0);

/// Σ c[m] y^m for m < 10 (c[9] = 0 where N is 9), by Estrin's scheme: pairs of terms, then
/// pairs of pairs, so that the multiplications overlap instead of waiting on each other as in
/// Horner's form.
template <size_t N>
inline double estrin(const std::array<double, N>& c, double y) {
  static_assert(N == 9 || N == 10);
  const double y2 = y * y, y4 = y2 * y2, y8 = y4 * y4;
  const double p0 = c[0] + c[1] * y, p1 = c[2] + c[3] * y;
  const double p2 = c[4] + c[5] * y, p3 = c[6] + c[7] * y;
  double p4 = c[8];
  if constexpr (N == 10) p4 += c[9] * y;
  return ((p0 + p1 * y2) + (p2 + p3 * y2) * y4) + p4 * y8;
}

}  // namespace warp_detail

/// sin x and cos x for |x| ≤ π/4 to within 2 ulps, without range reduction: the angles of the
/// concentric map, which every diffuse bounce draws, at a fraction of std::sin and std::cos.
/// sin x = x Σ (−1)^m x^2m / (2m + 1)! to x¹⁷ and cos x = Σ (−1)^m x^2m / (2m)! to x¹⁸, as
/// polynomials in x²; the first terms left out, x¹⁹/19! and x²⁰/20!, are below 1e-19 for
/// |x| ≤ π/4, far under half an ulp of either.
inline void sinCosQuarter(double x, double& s, double& c) {
  const double x2 = x * x;
  s = x * warp_detail::estrin(warp_detail::kSinSeries, x2);
  c = warp_detail::estrin(warp_detail::kCosSeries, x2);
}

/// Concentric map (Shirley & Chiu 1997) to the unit disk: uniform, area-preserving, low distortion.
inline Vec2 squareToUniformDiskConcentric(const Vec2& u) {
  const double a = 2.0 * u.x() - 1.0, b = 2.0 * u.y() - 1.0;
  if (a == 0.0 && b == 0.0) return Vec2::Zero();
  // Squares of side 2r map to circles of radius r; each wedge between diagonals to its sector:
  // φ = (π/4)(b/a) in the wedges around ±x, φ = π/2 − (π/4)(a/b) around ±y, where cos φ and
  // sin φ swap to the sine and cosine of (π/4)(a/b). Either way the angle to evaluate lies in
  // [−π/4, π/4], where sinCosQuarter needs no range reduction.
  double s, c;
  if (std::abs(a) > std::abs(b)) {
    sinCosQuarter((kPi / 4.0) * (b / a), s, c);
    return Vec2(a * c, a * s);
  }
  sinCosQuarter((kPi / 4.0) * (a / b), s, c);
  return Vec2(b * s, b * c);
}
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
inline Vec3 squareToCosineHemisphere(const Vec2& u) {
  const Vec2 d = squareToUniformDiskConcentric(u);
  return Vec3(d.x(), d.y(), std::sqrt(std::max(0.0, 1.0 - d.squaredNorm())));
}
/// cos θ / π for z ≥ 0.
inline double squareToCosineHemispherePdf(const Vec3& v) {
  return v.z() >= 0.0 ? v.z() * kInvPi : 0.0;
}

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
