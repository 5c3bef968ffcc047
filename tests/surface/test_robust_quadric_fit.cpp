#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <random>

#include "quadtri/mesh/shapes.h"
#include "quadtri/mesh/topology.h"
#include "quadtri/surface/robust_implicit_model.h"
#include "quadtri/surface/robust_quadric_fit.h"
#include "surface/robust_fixtures.h"

namespace quadtri {
namespace {

using namespace robust_test;

TEST(RobustQuadricFit, CornersAreExactOnRandomTriangles) {
  Rng rng(1);
  for (int trial = 0; trial < 500; ++trial) {
    const double scale = std::pow(10.0, uniform(rng, -3, 3));
    const Vec3 offset = scale * uniform(rng, 0, 100) * randomUnit(rng);
    CornerData d;
    for (int k = 0; k < 3; ++k)
      d.position[k] =
          offset + scale * Vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
    const Vec3 face =
        (d.position[1] - d.position[0]).cross(d.position[2] - d.position[0]).normalized();
    for (int k = 0; k < 3; ++k) d.normal[k] = (face + 0.9 * randomUnit(rng)).normalized();
    for (int k = 0; k < 3; ++k)
      d.arcMidpoint[k] = edgeArcMidpoint(d.position[k], d.normal[k], d.position[(k + 1) % 3],
                                         d.normal[(k + 1) % 3]);
    const QuadricFit fit = fitQuadric(d);
    for (double c : fit.q) ASSERT_TRUE(std::isfinite(c));
    for (int k = 0; k < 3; ++k) {
      // Relative to the magnitude of the terms summed: far from the origin, evaluating a
      // world-space quadric loses digits however exact the fit is.
      const Vec3& p = d.position[k];
      const QuadricCoeffs& q = fit.q;
      const double terms = std::abs(q[0] * p.x() * p.x()) + std::abs(q[1] * p.y() * p.y()) +
                           std::abs(q[2] * p.z() * p.z()) + std::abs(q[3] * p.x() * p.y()) +
                           std::abs(q[4] * p.x() * p.z()) + std::abs(q[5] * p.y() * p.z()) +
                           std::abs(q[6] * p.x()) + std::abs(q[7] * p.y()) +
                           std::abs(q[8] * p.z()) + std::abs(q[9]);
      EXPECT_LT(std::abs(evalQuadric(q, p)) / terms, 1e-12) << trial;
    }
    // No corner's gradient turns against its normal, however inconsistent the normals.
    for (int k = 0; k < 3; ++k)
      EXPECT_GT(quadricGradient(fit.q, d.position[k]).dot(d.normal[k]), 0.0) << trial;
  }
}

TEST(RobustQuadricFit, QuadricDataGiveExactCornerNormalsAndThePencilOfTheQuadric) {
  // Any quadric's data satisfy the tangency exactly, and the fit lies in the pencil
  // {that quadric, L²}: it contains the quadric's section by the triangle's plane and is
  // tangent to it along that conic. Only the sphere is pinned down by the arc midpoints.
  Rng rng(2);
  const Surface surfaces[] = {ellipsoid(1.0, 0.7, 0.5), cylinder(0.8), saddle(),
                              sphere(Vec3(0.3, -0.2, 0.1), 0.9)};
  for (int s = 0; s < 4; ++s)
    for (int trial = 0; trial < 50; ++trial) {
      const CornerData d = sampleTriangle(surfaces[s], randomUnit(rng) * uniform(rng, 0.2, 1.2),
                                          uniform(rng, 0.05, 0.4), rng);
      const QuadricFit fit = fitQuadric(d);
      EXPECT_LT(fit.cornerNormalErrorDeg * kPi / 180, 1e-9) << s << " " << trial;
      EXPECT_LT(distanceToPencil(fit.q, surfaces[s].coefficients, planeSquared(d)), 1e-9)
          << s << " " << trial;
    }
}

TEST(RobustQuadricFit, GenericDataHaveNoExactQuadricButConvergeAtSecondOrder) {
  // A torus is no quadric: the tangency conditions are incompatible, the least corner-normal
  // error is positive, and it falls ~4× when the triangle halves (O(h²)).
  Rng rng(3);
  const Surface s = torus(1.0, 0.35);
  for (int trial = 0; trial < 20; ++trial) {
    const double angle = uniform(rng, 0, 2 * kPi), tube = uniform(rng, 0, 2 * kPi);
    const Vec3 at((1 + 0.35 * std::cos(tube)) * std::cos(angle),
                  (1 + 0.35 * std::cos(tube)) * std::sin(angle), 0.35 * std::sin(tube));
    Rng a = rng, b = rng;
    const double coarse = fitQuadric(sampleTriangle(s, at, 0.08, a)).cornerNormalErrorDeg;
    const double fine = fitQuadric(sampleTriangle(s, at, 0.04, b)).cornerNormalErrorDeg;
    rng.discard(20);
    EXPECT_GT(coarse, 1e-6) << trial;
    EXPECT_LT(coarse, 1.0) << trial;
    EXPECT_GT(coarse / fine, 3.0) << trial;
  }
}

TEST(RobustQuadricFit, SimilarityTransformsCommuteWithTheFit) {
  Rng rng(4);
  const Surface s = torus(1.0, 0.35);
  for (int trial = 0; trial < 50; ++trial) {
    const CornerData d = sampleTriangle(s, randomUnit(rng) * 1.2, 0.15, rng);
    const double scale = std::pow(10.0, uniform(rng, -6, 6));
    const Mat3 R = randomRotation(rng);
    const Vec3 shift = scale * uniform(rng, 0, 10) * randomUnit(rng);
    CornerData moved = d;
    for (int k = 0; k < 3; ++k) {
      moved.position[k] = scale * R * d.position[k] + shift;
      moved.normal[k] = R * d.normal[k];
      moved.arcMidpoint[k] = scale * R * d.arcMidpoint[k] + shift;
    }
    const QuadricCoeffs q = fitQuadric(d).q, qm = fitQuadric(moved).q;
    // Pull qm back: q'(x) = qm(scale R x + shift), expanded through its 4×4 matrix.
    Mat4 Q;
    Q << qm[0], qm[3] / 2, qm[4] / 2, qm[6] / 2, qm[3] / 2, qm[1], qm[5] / 2, qm[7] / 2, qm[4] / 2,
        qm[5] / 2, qm[2], qm[8] / 2, qm[6] / 2, qm[7] / 2, qm[8] / 2, qm[9];
    Mat4 A = Mat4::Identity();
    A.block<3, 3>(0, 0) = scale * R;
    A.block<3, 1>(0, 3) = shift;
    const Mat4 P = A.transpose() * Q * A;
    const QuadricCoeffs back = {P(0, 0),     P(1, 1),     P(2, 2),     2 * P(0, 1), 2 * P(0, 2),
                                2 * P(1, 2), 2 * P(0, 3), 2 * P(1, 3), 2 * P(2, 3), P(3, 3)};
    EXPECT_LT(proportionalityError(q, back), 1e-7) << trial << " scale " << scale;
  }
}

TEST(RobustQuadricFit, FlatDataGiveTheirPlane) {
  Rng rng(5);
  for (int trial = 0; trial < 100; ++trial) {
    const Mat3 R = randomRotation(rng);
    const double scale = std::pow(10.0, uniform(rng, -4, 4));
    const Vec3 shift = scale * uniform(rng, 0, 10) * randomUnit(rng);
    CornerData d;
    for (int k = 0; k < 3; ++k) {
      d.position[k] = shift + scale * R * Vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), 0);
      d.normal[k] = R.col(2);
    }
    for (int k = 0; k < 3; ++k)
      d.arcMidpoint[k] = edgeArcMidpoint(d.position[k], d.normal[k], d.position[(k + 1) % 3],
                                         d.normal[(k + 1) % 3]);
    const QuadricFit fit = fitQuadric(d);
    const Vec3 n = R.col(2);
    const QuadricCoeffs plane = {0, 0, 0, 0, 0, 0, n.x(), n.y(), n.z(), -n.dot(shift)};
    EXPECT_LT(proportionalityError(fit.q, plane), 1e-9) << trial;
    EXPECT_LT(fit.cornerNormalErrorDeg, 1e-9);
  }
}

TEST(RobustQuadricFit, NearlyFlatDataApproachThePlaneContinuously) {
  // Sphere caps of growing radius: the fit stays the sphere while the data determine it and
  // meets the plane continuously, never jumping to another quadric.
  Rng rng(6);
  for (double radius : {1e1, 1e3, 1e5, 1e7, 1e9}) {
    const Surface s = sphere(Vec3(0, 0, -radius), radius);
    const CornerData d = sampleTriangle(s, Vec3(0, 0, 0), 1.0, rng);
    const QuadricFit fit = fitQuadric(d);
    for (double c : fit.q) ASSERT_TRUE(std::isfinite(c));
    // On the patch's own extent the fitted surface is the cap to within ~ε·h.
    for (int k = 0; k < 3; ++k) {
      const Vec3 p = d.arcMidpoint[k];
      const Vec3 g = quadricGradient(fit.q, p);
      EXPECT_LT(std::abs(evalQuadric(fit.q, p)) / g.norm(), 1e-9) << radius;
    }
  }
}

TEST(RobustQuadricFit, DegenerateTrianglesGiveFiniteCoefficients) {
  const Vec3 n(0, 0, 1);
  const std::array<std::array<Vec3, 3>, 3> triangles = {
      {{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)},
       {Vec3(1, 1, 1), Vec3(1, 1, 1), Vec3(1, 1, 1)},
       {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 0, 0)}}};
  for (const auto& tri : triangles)
    for (const Vec3& n2 : {n, Vec3(-n), Vec3(1, 0, 0)}) {
      CornerData d;
      d.position = tri;
      d.normal = {n, n2, n};
      for (int k = 0; k < 3; ++k)
        d.arcMidpoint[k] = edgeArcMidpoint(d.position[k], d.normal[k], d.position[(k + 1) % 3],
                                           d.normal[(k + 1) % 3]);
      const QuadricFit fit = fitQuadric(d);
      for (double c : fit.q) EXPECT_TRUE(std::isfinite(c));
      EXPECT_TRUE(std::isfinite(fit.cornerNormalErrorDeg));
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(evalQuadric(fit.q, tri[k]), 0.0, 1e-12);
    }
}

TEST(EdgeArc, MidpointLiesOnTheSphereAndIsSymmetric) {
  Rng rng(7);
  for (int trial = 0; trial < 100; ++trial) {
    const Vec3 c = randomUnit(rng) * 3;
    const double r = uniform(rng, 0.1, 10);
    const Vec3 a = randomUnit(rng),
               b = (a + uniform(rng, 0.05, 1.5) * randomUnit(rng)).normalized();
    const Vec3 m = edgeArcMidpoint(c + r * a, a, c + r * b, b);
    EXPECT_NEAR((m - c).norm(), r, 1e-12 * r);
    EXPECT_LT((m - edgeArcMidpoint(c + r * b, b, c + r * a, a)).norm(), 1e-14 * (r + 3));
  }
}

}  // namespace
}  // namespace quadtri
