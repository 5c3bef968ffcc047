// Shared inputs for the surface model tests: random triangles with random shading normals and
// one-triangle meshes built from them.
#pragma once

#include <Eigen/SVD>
#include <array>
#include <memory>
#include <random>

#include "quadtri/mesh/triangle_mesh.h"
#include "quadtri/surface/edge_curves.h"

namespace quadtri::test {

/// Corners and unit shading normals of one triangle.
struct TriangleData {
  std::array<Vec3, 3> v;
  std::array<Vec3, 3> n;
};

/// A unit vector uniformly distributed in the cone of half-angle maxDegrees around unit axis.
inline Vec3 randomInCone(std::mt19937_64& rng, const Vec3& axis, double maxDegrees) {
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  const double cosMax = std::cos(maxDegrees * kPi / 180.0);
  const double cosTheta = 1.0 - uni(rng) * (1.0 - cosMax);
  const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
  const double phi = 2.0 * kPi * uni(rng);
  Vec3 s, t;
  orthonormalBasis(axis, s, t);
  return (cosTheta * axis + sinTheta * (std::cos(phi) * s + std::sin(phi) * t)).normalized();
}

/// A triangle with corners in [-1, 1]³, every angle at least minAngleDegrees, and shading
/// normals within maxNormalDegrees of its face normal.
inline TriangleData randomTriangle(std::mt19937_64& rng, double maxNormalDegrees = 60.0,
                                   double minAngleDegrees = 15.0) {
  std::uniform_real_distribution<double> coord(-1.0, 1.0);
  for (;;) {
    TriangleData d;
    for (Vec3& p : d.v) p = Vec3(coord(rng), coord(rng), coord(rng));
    bool fat = true;
    for (int k = 0; k < 3; ++k) {
      const Vec3 a = d.v[(k + 1) % 3] - d.v[k], b = d.v[(k + 2) % 3] - d.v[k];
      fat &= angleDegrees(a, b) >= minAngleDegrees;
    }
    if (!fat) continue;
    const Vec3 face = (d.v[1] - d.v[0]).cross(d.v[2] - d.v[0]).normalized();
    for (Vec3& n : d.n) n = randomInCone(rng, face, maxNormalDegrees);
    return d;
  }
}

/// Thesis eq. 4.5: the normal of the plane through vi, vj and (vi+vj)/2 + (ni+nj)/2.
inline Vec3 edgePlaneNormal(const Vec3& vi, const Vec3& ni, const Vec3& vj, const Vec3& nj) {
  const Vec3 displaced = 0.5 * (vi + vj) + 0.5 * (ni + nj);
  return (vj - vi).cross(displaced - vi);
}

/// Smallest singular value over d's three edge systems (rows ni, nj, unit edge-plane normal):
/// where it is small the closed form's damping (relative effect 1e-14/σ²) shows.
inline double edgeSystemSigmaMin(const TriangleData& d) {
  double sigma = kInfinity;
  for (int k = 0; k < 3; ++k) {
    const int i = k, j = (k + 1) % 3;
    Mat3 M;
    M.row(0) = d.n[i];
    M.row(1) = d.n[j];
    M.row(2) = edgePlaneNormal(d.v[i], d.n[i], d.v[j], d.n[j]).normalized();
    const Eigen::JacobiSVD<Mat3> svd(M);
    const Vec3 singular = svd.singularValues();
    sigma = std::min(sigma, singular.minCoeff());
  }
  return sigma;
}

/// Whether the exact control point of edge k lies within the closed form's bound (one edge
/// length from the chord midpoint), so that edgeControlPoint returns it unclamped. Independent
/// random normals often ask for an S-shaped edge, which no quadratic has: then the exact
/// point is far away and gets clamped.
inline bool edgeUnclamped(const TriangleData& d, int k) {
  const Vec3 &a = d.v[k], &b = d.v[(k + 1) % 3];
  const Vec3 c = edgeControlPoint(a, d.n[k], b, d.n[(k + 1) % 3]);
  return (c - 0.5 * (a + b)).norm() < 0.999 * (b - a).norm();
}

/// The one-triangle mesh of d, with one normal per corner.
inline std::shared_ptr<const TriangleMesh> triangleMesh(const TriangleData& d) {
  auto m = std::make_shared<TriangleMesh>();
  m->positions.assign(d.v.begin(), d.v.end());
  m->normals.assign(d.n.begin(), d.n.end());
  m->triangles = {{0, 1, 2}};
  m->normalIndices = {{0, 1, 2}};
  return m;
}

/// The barycentric (u, v) of corner k: (0,0), (1,0), (0,1).
inline Vec2 cornerUv(int k) {
  return k == 0 ? Vec2(0, 0) : k == 1 ? Vec2(1, 0) : Vec2(0, 1);
}

/// The (u, v) of the point at parameter s on local edge k, from corner k to corner k+1.
inline Vec2 edgeUv(int k, double s) {
  return (1.0 - s) * cornerUv(k) + s * cornerUv((k + 1) % 3);
}

}  // namespace quadtri::test
