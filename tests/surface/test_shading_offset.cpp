// The shadow-terminator offset of `shading-offset` (Hanika 2021) and the model that uses it.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <nlohmann/json.hpp>

#include "quadtri/mesh/shapes.h"
#include "quadtri/surface/model.h"
#include "quadtri/surface/shading_offset.h"
#include "surface_fixtures.h"

namespace quadtri::test {
namespace {

Vec3 randomBarycentric(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  double u = uni(rng), v = uni(rng);
  if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
  return Vec3(1.0 - u - v, u, v);
}

TEST(ShadingOffset, CornersReproduceTheirVertices) {
  std::mt19937_64 rng(11);
  for (int i = 0; i < 1000; ++i) {
    const TriangleData d = randomTriangle(rng, 80.0);
    for (int k = 0; k < 3; ++k) {
      Vec3 b = Vec3::Zero();
      b[k] = 1.0;
      EXPECT_EQ(shadingOffsetPoint(d.v, d.n, b), d.v[k]) << "triangle " << i << " corner " << k;
    }
  }
}

TEST(ShadingOffset, IdentityOnFlatData) {
  // Every normal equal to the face normal: p lies on every corner's tangent plane.
  std::mt19937_64 rng(12);
  for (int i = 0; i < 1000; ++i) {
    TriangleData d = randomTriangle(rng);
    const Vec3 face = (d.v[1] - d.v[0]).cross(d.v[2] - d.v[0]).normalized();
    for (const Vec3& normal : {face, Vec3(-face)}) {
      d.n = {normal, normal, normal};
      const Vec3 b = randomBarycentric(rng);
      const Vec3 p = b[0] * d.v[0] + b[1] * d.v[1] + b[2] * d.v[2];
      EXPECT_LT((shadingOffsetPoint(d.v, d.n, b) - p).norm(), 1e-14) << "triangle " << i;
    }
  }
}

TEST(ShadingOffset, MatchesHanikasProjectionOnRandomTriangles) {
  // p' = Σ bᵢ(vᵢ + tᵢ), tᵢ = p − vᵢ projected onto vᵢ's tangent plane where tᵢ·nᵢ < 0: written
  // out here term by term, and compared with the closed form p + Σ bᵢ max(0, −tᵢ·nᵢ) nᵢ.
  std::mt19937_64 rng(13);
  int lifted = 0;
  for (int i = 0; i < 2000; ++i) {
    const TriangleData d = randomTriangle(rng, 50.0);
    const Vec3 b = randomBarycentric(rng);
    const Vec3 p = b[0] * d.v[0] + b[1] * d.v[1] + b[2] * d.v[2];
    Vec3 expected = Vec3::Zero();
    for (int k = 0; k < 3; ++k) {
      Vec3 t = p - d.v[k];
      if (t.dot(d.n[k]) < 0.0) t -= t.dot(d.n[k]) * d.n[k];
      expected += b[k] * (d.v[k] + t);
    }
    const Vec3 got = shadingOffsetPoint(d.v, d.n, b);
    // Cones of 50° keep every normal on the face's side, so nothing falls back to p here.
    EXPECT_LT((got - expected).norm(), 1e-14) << "triangle " << i;
    lifted += (got - p).norm() > 1e-6;
  }
  EXPECT_GT(lifted, 500);
}

TEST(ShadingOffset, LiftsIcosphereTowardsTheSphere) {
  // Level 1 (80 triangles) carries the unit sphere's normals. A point of a face lies inside the
  // sphere; its lifted point moves outwards, never below the face's plane, and on average ends
  // closer to the sphere. The lift is a quadratic height field, not the sphere: at an edge
  // midpoint m of (v₀, v₁) with c = v₀·v₁ both corners lift it by (1 − c)/4 along their normal,
  // to radius √((1 + c)/2) + (1 − c)/4·√(2 + 2c), past the sphere (1.041 here).
  ShapeParams params;
  params.level = 1;
  const TriangleMesh mesh = makeBuiltin("icosphere", params).mesh;
  std::mt19937_64 rng(14);
  double worstFlatGap = 0.0, worstLiftedGap = 0.0, sumFlatGap = 0.0, sumLiftedGap = 0.0;
  int samples = 0;
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    const Vec3 face = mesh.faceNormal(t);
    ASSERT_GT(face.dot(mesh.corner(t, 0)), 0.0) << "outward winding";
    for (int i = 0; i < 200; ++i) {
      const Vec3 b = randomBarycentric(rng);
      const Vec3 p = b[0] * mesh.corner(t, 0) + b[1] * mesh.corner(t, 1) + b[2] * mesh.corner(t, 2);
      const Vec3 q = shadingOffsetPoint(mesh, t, b);
      ASSERT_TRUE(allFinite(q));
      EXPECT_GE((q - p).dot(face), 0.0) << "below the plane: triangle " << t;
      EXPECT_GE(q.norm(), p.norm() - 1e-15) << "triangle " << t;
      worstFlatGap = std::max(worstFlatGap, 1.0 - p.norm());
      worstLiftedGap = std::max(worstLiftedGap, std::abs(1.0 - q.norm()));
      sumFlatGap += 1.0 - p.norm();
      sumLiftedGap += std::abs(1.0 - q.norm());
      ++samples;
    }
    for (int k = 0; k < 3; ++k) {
      Vec3 b = Vec3::Constant(0.5);
      b[(k + 2) % 3] = 0.0;
      const Vec3 &v0 = mesh.corner(t, k), &v1 = mesh.corner(t, (k + 1) % 3);
      const double c = v0.dot(v1);
      const Vec3 expected = 0.5 * (v0 + v1) + 0.25 * (1.0 - c) * (v0 + v1);
      EXPECT_LT((shadingOffsetPoint(mesh, t, b) - expected).norm(), 1e-15);
      EXPECT_NEAR(expected.norm(),
                  std::sqrt((1.0 + c) / 2.0) + 0.25 * (1.0 - c) * std::sqrt(2.0 + 2.0 * c), 1e-15);
    }
  }
  // Measured: worst gap 0.066 flat, 0.053 lifted (the overshoot at edge midpoints); mean gap
  // 0.044 flat, 0.037 lifted.
  EXPECT_NEAR(worstFlatGap, 0.066, 0.002);
  EXPECT_LT(worstLiftedGap, 0.06);
  EXPECT_LT(sumLiftedGap / samples, 0.9 * sumFlatGap / samples);
}

TEST(ShadingOffset, InvariantUnderSimilarity) {
  std::mt19937_64 rng(15);
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.7, Vec3(1, 2, -0.5).normalized()).toRotationMatrix();
  for (double scale : {1e-6, 1.0, 1e6}) {
    const Vec3 shift = Vec3(3, -1, 2) * scale;
    for (int i = 0; i < 200; ++i) {
      const TriangleData d = randomTriangle(rng, 60.0);
      TriangleData moved;
      for (int k = 0; k < 3; ++k) {
        moved.v[k] = scale * (rotation * d.v[k]) + shift;
        moved.n[k] = rotation * d.n[k];
      }
      const Vec3 b = randomBarycentric(rng);
      const Vec3 expected = scale * (rotation * shadingOffsetPoint(d.v, d.n, b)) + shift;
      EXPECT_LT((shadingOffsetPoint(moved.v, moved.n, b) - expected).norm(), 1e-12 * scale * 4)
          << "scale " << scale << " triangle " << i;
    }
  }
}

TEST(ShadingOffset, DegenerateInputFallsBackToThePoint) {
  const Vec3 b(0.2, 0.3, 0.5);
  const std::array<Vec3, 3> n = {Vec3(-0.3, 0, 1).normalized(), Vec3(0.3, 0, 1).normalized(),
                                 Vec3(0, 0.4, 1).normalized()};
  const std::array<Vec3, 3> v = {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(0, 1, 0)};
  const Vec3 p = b[0] * v[0] + b[1] * v[1] + b[2] * v[2];
  ASSERT_GT((shadingOffsetPoint(v, n, b) - p).norm(), 1e-3) << "the healthy case lifts";
  // Collinear and coincident corners.
  const std::array<Vec3, 3> line = {Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(2, 2, 2)};
  EXPECT_EQ(shadingOffsetPoint(line, n, b), b[0] * line[0] + b[1] * line[1] + b[2] * line[2]);
  const std::array<Vec3, 3> point = {Vec3(1, 2, 3), Vec3(1, 2, 3), Vec3(1, 2, 3)};
  EXPECT_TRUE(allFinite(shadingOffsetPoint(point, n, b)));
  EXPECT_EQ(shadingOffsetPoint(point, n, b), b[0] * point[0] + b[1] * point[1] + b[2] * point[2]);
  // Zero, infinite and NaN normals.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const Vec3& bad : {Vec3(0, 0, 0), Vec3(inf, 0, 1), Vec3(nan, 0, 1)}) {
    std::array<Vec3, 3> broken = n;
    broken[1] = bad;
    EXPECT_EQ(shadingOffsetPoint(v, broken, b), p);
  }
  // A normal facing away from its triangle would pull p' below the plane: p instead.
  std::array<Vec3, 3> away = n;
  away[2] = Vec3(0, 0.4, -1).normalized();
  const Vec3 q = shadingOffsetPoint(v, away, b);
  EXPECT_GE(q.z(), 0.0);
  // Non-unit normals are normalised first.
  const std::array<Vec3, 3> long_ = {5.0 * n[0], 0.1 * n[1], 3.0 * n[2]};
  EXPECT_LT((shadingOffsetPoint(v, long_, b) - shadingOffsetPoint(v, n, b)).norm(), 1e-15);
}

TEST(ShadingOffset, ModelIsShadingWithLiftedOrigins) {
  const std::vector<std::string>& names = modelNames();
  const auto shading = std::find(names.begin(), names.end(), "shading");
  ASSERT_NE(shading, names.end());
  ASSERT_NE(shading + 1, names.end());
  EXPECT_EQ(*(shading + 1), "shading-offset");
  const auto mesh = std::make_shared<const TriangleMesh>(makeBuiltin("icosahedron").mesh);
  const auto offset = makeModel("shading-offset", mesh);
  const auto plain = makeModel("shading", mesh);
  EXPECT_EQ(offset->name(), "shading-offset");
  EXPECT_EQ(offset->representation(), Representation::InputTriangles);
  EXPECT_TRUE(offset->interpolatesShadingNormals());
  EXPECT_TRUE(offset->liftsRayOrigins());
  EXPECT_FALSE(plain->liftsRayOrigins());
  EXPECT_FALSE(makeModel("flat", mesh)->liftsRayOrigins());
  EXPECT_FALSE(makeModel("quadric-param", mesh)->liftsRayOrigins());
  for (size_t t = 0; t < mesh->triangleCount(); ++t) {
    const SurfacePoint a = offset->evaluate(t, 0.3, 0.2), b = plain->evaluate(t, 0.3, 0.2);
    EXPECT_EQ(a.position, b.position);
    EXPECT_EQ(a.normal, b.normal);
    EXPECT_EQ(offset->patchJson(t), plain->patchJson(t));
  }
}

}  // namespace
}  // namespace quadtri::test
