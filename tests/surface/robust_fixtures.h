// Shared fixtures of the robust implicit model's tests: sampled quadric and non-quadric
// surfaces, random similarity transforms and coefficient comparisons.
#pragma once

#include <functional>
#include <random>

#include "quadtri/surface/robust_quadric_fit.h"

namespace quadtri::robust_test {

using Rng = std::mt19937_64;

inline double uniform(Rng& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

inline Vec3 randomUnit(Rng& rng) {
  std::normal_distribution<double> g;
  return Vec3(g(rng), g(rng), g(rng)).normalized();
}

inline Mat3 randomRotation(Rng& rng) {
  std::normal_distribution<double> g;
  return Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
}

// A smooth surface sampled by the tests: implicit function, its gradient and a sampler.
struct Surface {
  std::function<double(const Vec3&)> value;
  std::function<Vec3(const Vec3&)> gradient;
  QuadricCoeffs coefficients{};  // when the surface is a quadric
};

inline Surface sphere(const Vec3& c, double r) {
  return {[=](const Vec3& p) { return (p - c).squaredNorm() - r * r; },
          [=](const Vec3& p) { return Vec3(2 * (p - c)); },
          {1, 1, 1, 0, 0, 0, -2 * c.x(), -2 * c.y(), -2 * c.z(), c.squaredNorm() - r * r}};
}
// x²/a² + y²/b² + z²/c² = 1.
inline Surface ellipsoid(double a, double b, double c) {
  return {[=](const Vec3& p) {
            return p.x() * p.x() / (a * a) + p.y() * p.y() / (b * b) + p.z() * p.z() / (c * c) - 1;
          },
          [=](const Vec3& p) {
            return Vec3(2 * p.x() / (a * a), 2 * p.y() / (b * b), 2 * p.z() / (c * c));
          },
          {1 / (a * a), 1 / (b * b), 1 / (c * c), 0, 0, 0, 0, 0, 0, -1}};
}
// x² + y² = r² (axis z).
inline Surface cylinder(double r) {
  return {[=](const Vec3& p) { return p.x() * p.x() + p.y() * p.y() - r * r; },
          [=](const Vec3& p) { return Vec3(2 * p.x(), 2 * p.y(), 0); },
          {1, 1, 0, 0, 0, 0, 0, 0, 0, -r * r}};
}
// z = x² − y², written x² − y² − z = 0.
inline Surface saddle() {
  return {[](const Vec3& p) { return p.x() * p.x() - p.y() * p.y() - p.z(); },
          [](const Vec3& p) { return Vec3(2 * p.x(), -2 * p.y(), -1); },
          {1, -1, 0, 0, 0, 0, 0, 0, -1, 0}};
}
// Torus around z with radii R, r (quartic, so no quadric contains it).
inline Surface torus(double R, double r) {
  return {[=](const Vec3& p) {
            const double s = p.squaredNorm() + R * R - r * r;
            return s * s - 4 * R * R * (p.x() * p.x() + p.y() * p.y());
          },
          [=](const Vec3& p) {
            const double s = p.squaredNorm() + R * R - r * r;
            return Vec3(4 * s * p.x() - 8 * R * R * p.x(), 4 * s * p.y() - 8 * R * R * p.y(),
                        4 * s * p.z());
          },
          {}};
}

// Newton steps along the gradient onto the zero set.
inline Vec3 projectOnto(const Surface& s, Vec3 p) {
  for (int i = 0; i < 60; ++i) {
    const Vec3 g = s.gradient(p);
    p -= s.value(p) / g.squaredNorm() * g;
  }
  return p;
}

// Corner data for a triangle of size h around point `at` on surface s, tangent-plane offsets.
inline CornerData sampleTriangle(const Surface& s, const Vec3& at, double h, Rng& rng,
                                 Vec3 orient = Vec3::Zero()) {
  const Vec3 base = projectOnto(s, at);
  Vec3 n = s.gradient(base).normalized();
  if (orient.squaredNorm() > 0 && n.dot(orient) < 0) n = -n;
  Vec3 t1, t2;
  orthonormalBasis(n, t1, t2);
  CornerData d;
  for (int k = 0; k < 3; ++k) {
    const double a = 2 * kPi * k / 3 + uniform(rng, -0.4, 0.4);
    const Vec3 p =
        projectOnto(s, base + h * uniform(rng, 0.6, 1.0) * (std::cos(a) * t1 + std::sin(a) * t2));
    d.position[k] = p;
    Vec3 nk = s.gradient(p).normalized();
    d.normal[k] = nk.dot(n) < 0 ? Vec3(-nk) : nk;
  }
  for (int k = 0; k < 3; ++k)
    d.arcMidpoint[k] =
        edgeArcMidpoint(d.position[k], d.normal[k], d.position[(k + 1) % 3], d.normal[(k + 1) % 3]);
  return d;
}

inline Eigen::Matrix<double, 10, 1> asVector(const QuadricCoeffs& q) {
  return Eigen::Map<const Eigen::Matrix<double, 10, 1>>(q.data());
}

// Largest coefficient difference between unit-norm, sign-aligned a and b.
inline double proportionalityError(const QuadricCoeffs& a, const QuadricCoeffs& b) {
  Eigen::Matrix<double, 10, 1> va = asVector(a).normalized(), vb = asVector(b).normalized();
  if (va.dot(vb) < 0) vb = -vb;
  return (va - vb).cwiseAbs().maxCoeff();
}

// Residual of q after removing its least-squares part in span{a, b} (all unit-normalised).
inline double distanceToPencil(const QuadricCoeffs& q, const QuadricCoeffs& a,
                               const QuadricCoeffs& b) {
  Eigen::Matrix<double, 10, 2> basis;
  basis.col(0) = asVector(a).normalized();
  basis.col(1) = asVector(b).normalized();
  const Eigen::Matrix<double, 10, 1> v = asVector(q).normalized();
  const Eigen::Vector2d x = basis.colPivHouseholderQr().solve(v);
  return (basis * x - v).norm();
}

inline QuadricCoeffs planeSquared(const CornerData& d) {
  const Vec3 n = (d.position[1] - d.position[0]).cross(d.position[2] - d.position[0]).normalized();
  const double e = -n.dot(d.position[0]);
  return {n.x() * n.x(),     n.y() * n.y(), n.z() * n.z(), 2 * n.x() * n.y(), 2 * n.x() * n.z(),
          2 * n.y() * n.z(), 2 * e * n.x(), 2 * e * n.y(), 2 * e * n.z(),     e * e};
}

}  // namespace quadtri::robust_test
