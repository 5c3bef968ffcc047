#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "fixtures/bezier_pieces.h"
#include "fixtures/sanitized.h"
#include "quadtri/geometry/rng.h"
#include "quadtri/surface/bezier_intersect.h"

namespace quadtri {
namespace {

using fixtures::bumpyPiece;
using fixtures::flatPiece;
using fixtures::paraboloidPiece;

// A uniform point of the triangle domain.
Vec2 domainPoint(Pcg32& rng) {
  double u = rng.nextDouble(), v = rng.nextDouble();
  if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
  return Vec2(u, v);
}

// A direction within `degrees` of −z.
Vec3 downward(Pcg32& rng, double degrees) {
  const double c = std::cos(degrees * kPi / 180.0);
  const double z = 1.0 - (1.0 - c) * rng.nextDouble(), phi = 2.0 * kPi * rng.nextDouble();
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return Vec3(r * std::cos(phi), r * std::sin(phi), -z);
}

const Vec2 kA(-1.5, -1.0), kB(2.0, -0.5), kC(-0.5, 2.0);

TEST(BezierIntersect, SubdivisionReproducesThePiece) {
  Pcg32 rng(3);
  BezierTriangle piece = bumpyPiece(Vec3(0, 0, 0), Vec3(1, 0.1, 0), Vec3(0.2, 1, 0), 0.3, rng);
  for (Vec3& p : piece.b) p.x() += 0.1 * rng.nextDouble();
  piece.orientation = -1.0;
  piece.triangle = 7;
  piece.piece = 2;
  const auto sub = subdivideBezierTriangle(piece);
  const std::array<std::array<Vec2, 3>, 4> corners{{{Vec2(0, 0), Vec2(0.5, 0), Vec2(0, 0.5)},
                                                    {Vec2(0.5, 0), Vec2(1, 0), Vec2(0.5, 0.5)},
                                                    {Vec2(0, 0.5), Vec2(0.5, 0.5), Vec2(0, 1)},
                                                    {Vec2(0.5, 0.5), Vec2(0, 0.5), Vec2(0.5, 0)}}};
  for (size_t m = 0; m < 4; ++m) {
    EXPECT_EQ(sub[m].orientation, -1.0);
    EXPECT_EQ(sub[m].triangle, 7u);
    EXPECT_EQ(sub[m].piece, 2);
    for (const Vec3& p : sub[m].b) {
      EXPECT_TRUE((p.array() >= sub[m].bounds().lo.array()).all());
      EXPECT_TRUE((p.array() <= sub[m].bounds().hi.array()).all());
    }
    for (int i = 0; i < 50; ++i) {
      const Vec2 l = domainPoint(rng);
      const Vec2 uv = corners[m][0] + l.x() * (corners[m][1] - corners[m][0]) +
                      l.y() * (corners[m][2] - corners[m][0]);
      EXPECT_NEAR((sub[m].position(l.x(), l.y()) - piece.position(uv.x(), uv.y())).norm(), 0.0,
                  1e-14);
      EXPECT_NEAR((sub[m].normal(l.x(), l.y()) - piece.normal(uv.x(), uv.y())).norm(), 0.0, 1e-12);
    }
  }
}

// positionAndNormal, from one pass over the net, gives position() and normal() up to rounding.
TEST(BezierIntersect, PositionAndNormalTogether) {
  Pcg32 rng(5);
  for (int i = 0; i < 20; ++i) {
    BezierTriangle piece = bumpyPiece(Vec3(0, 0, 0), Vec3(1, 0.1, 0), Vec3(0.2, 1, 0), 0.5, rng);
    piece.orientation = i % 2 ? 1.0 : -1.0;
    for (int k = 0; k < 20; ++k) {
      const Vec2 uv = domainPoint(rng);
      Vec3 p, n;
      piece.positionAndNormal(uv.x(), uv.y(), p, n);
      EXPECT_NEAR((p - piece.position(uv.x(), uv.y())).norm(), 0.0, 1e-14);
      EXPECT_NEAR((n - piece.normal(uv.x(), uv.y())).norm(), 0.0, 1e-15);
      EXPECT_NEAR(n.norm(), 1.0, 1e-15);
    }
  }
}

TEST(BezierIntersect, FlatPieceReturnsTheAimedAtPoint) {
  const BezierTriangle piece =
      flatPiece(Vec3(0.3, -0.2, 1.0), Vec3(2.1, 0.4, 0.7), Vec3(0.1, 1.9, 1.5));
  const Vec3 n = (piece.b[14] - piece.b[0]).cross(piece.b[4] - piece.b[0]).normalized();
  Pcg32 rng(11);
  for (int i = 0; i < 2000; ++i) {
    const Vec2 uv = domainPoint(rng);
    const Vec3 target = piece.position(uv.x(), uv.y());
    const Vec3 origin = target + (0.5 + 3.0 * rng.nextDouble()) * uniformDirection(rng);
    const Vec3 d = target - origin;  // not unit: t = 1 at the target
    BezierHit hit;
    ASSERT_TRUE(intersectBezierTriangle(piece, origin, d, 0.0, kInfinity, hit)) << i;
    EXPECT_NEAR(hit.t, 1.0, 1e-9);
    EXPECT_NEAR(hit.u, uv.x(), 1e-9);
    EXPECT_NEAR(hit.v, uv.y(), 1e-9);
    EXPECT_NEAR(std::abs(piece.normal(hit.u, hit.v).dot(n)), 1.0, 1e-12);
    EXPECT_TRUE(occludesBezierTriangle(piece, origin, d, 0.0, 2.0));
    EXPECT_FALSE(occludesBezierTriangle(piece, origin, d, 0.0, 0.999));
    EXPECT_FALSE(intersectBezierTriangle(piece, origin, -d, 0.0, kInfinity, hit));
  }
}

// Origins above the bowl z ≥ x² + y² (a convex set): every ray from one leaves it exactly once.
TEST(BezierIntersect, ParaboloidReintersection) {
  const BezierTriangle piece = paraboloidPiece(kA, kB, kC);
  Pcg32 rng(5);
  std::vector<BezierHit> all;
  for (int i = 0; i < 20000; ++i) {
    const Vec2 uv = domainPoint(rng);
    const Vec3 target = piece.position(uv.x(), uv.y());
    ASSERT_NEAR(target.z(), target.x() * target.x() + target.y() * target.y(), 1e-12);
    const Vec2 xy(3.0 * rng.nextDouble() - 1.5, 3.0 * rng.nextDouble() - 1.5);
    const Vec3 origin(xy.x(), xy.y(), xy.squaredNorm() + 0.01 + 2.0 * rng.nextDouble());
    const double distance = (target - origin).norm();
    const Vec3 d = (target - origin) / distance;
    BezierHit hit;
    ASSERT_TRUE(intersectBezierTriangle(piece, origin, d, 0.0, kInfinity, hit)) << i;
    EXPECT_NEAR(hit.t, distance, 1e-9 * distance) << i;
    EXPECT_NEAR(hit.u, uv.x(), 1e-9) << i;
    EXPECT_NEAR(hit.v, uv.y(), 1e-9) << i;
    all.clear();
    EXPECT_EQ(intersectBezierTriangleAll(piece, origin, d, 0.0, kInfinity, all), 1u) << i;
    // tmin and tmax are respected on both sides of the hit.
    EXPECT_FALSE(intersectBezierTriangle(piece, origin, d, 0.0, distance * (1 - 1e-6), hit));
    EXPECT_FALSE(intersectBezierTriangle(piece, origin, d, distance * (1 + 1e-6), kInfinity, hit));
    EXPECT_FALSE(occludesBezierTriangle(piece, origin, d, 0.0, distance * (1 - 1e-6)));
    EXPECT_TRUE(intersectBezierTriangle(piece, origin, d, distance * (1 - 1e-6),
                                        distance * (1 + 1e-6), hit));
    // The normal is the bowl's inner normal (u × v turns towards +z for this winding).
    const Vec3 expected = Vec3(-2 * target.x(), -2 * target.y(), 1).normalized();
    EXPECT_NEAR((piece.normal(hit.u, hit.v) - expected).norm(), 0.0, 1e-9);
  }
}

TEST(BezierIntersect, RaysAimedOutsideTheDomainMiss) {
  const BezierTriangle piece = paraboloidPiece(kA, kB, kC);
  Pcg32 rng(9);
  int outside = 0;
  for (int i = 0; i < 20000; ++i) {
    // (u, v) up to 0.2 beyond one of the three edges, at least 1e-6 beyond.
    Vec2 uv = domainPoint(rng);
    const double beyond = 1e-6 + 0.2 * rng.nextDouble() * rng.nextDouble();
    const int edge = int(rng.nextUint() % 3);
    if (edge == 0) uv.y() = -beyond;
    if (edge == 1) uv.x() = -beyond;
    if (edge == 2) uv *= (1.0 + beyond) / (uv.sum() > 0 ? uv.sum() : 1.0);
    if (edge == 2 && uv.sum() <= 1.0) continue;
    ++outside;
    const Vec3 target = piece.position(uv.x(), uv.y());  // on the same paraboloid
    const Vec2 xy(3.0 * rng.nextDouble() - 1.5, 3.0 * rng.nextDouble() - 1.5);
    const Vec3 origin(xy.x(), xy.y(), xy.squaredNorm() + 0.01 + 2.0 * rng.nextDouble());
    BezierHit hit;
    EXPECT_FALSE(intersectBezierTriangle(piece, origin, target - origin, 0.0, kInfinity, hit))
        << i << " u " << uv.x() << " v " << uv.y() << " got " << hit.u << " " << hit.v;
  }
  EXPECT_GT(outside, 15000);
}

// Lines through the bowl below its rim cross it twice: both hits, at the quadratic's roots.
TEST(BezierIntersect, TwoHitsOnACurvedPiece) {
  const BezierTriangle piece = paraboloidPiece(Vec2(-8, -8), Vec2(16, -8), Vec2(-8, 16));
  Pcg32 rng(13);
  std::vector<BezierHit> all;
  for (int i = 0; i < 5000; ++i) {
    // A line through a point inside the bowl (z > x² + y², |x|, |y| < 1) with a direction
    // tilted at most ~30° from horizontal: both roots fall inside the domain.
    const Vec2 xy(2.0 * rng.nextDouble() - 1.0, 2.0 * rng.nextDouble() - 1.0);
    const Vec3 inside(xy.x(), xy.y(), xy.squaredNorm() + 0.5 * rng.nextDouble() + 1e-3);
    const double phi = 2.0 * kPi * rng.nextDouble();
    const Vec3 d(std::cos(phi), std::sin(phi), 0.5 * (2.0 * rng.nextDouble() - 1.0));
    const Vec3 origin = inside - 4.0 * d;
    // (o + t d) on z = x² + y²: a t² + b t + c = 0.
    const double a = d.x() * d.x() + d.y() * d.y();
    const double b = 2 * (origin.x() * d.x() + origin.y() * d.y()) - d.z();
    const double c = origin.x() * origin.x() + origin.y() * origin.y() - origin.z();
    const double disc = std::sqrt(b * b - 4 * a * c);
    const double q = -0.5 * (b + std::copysign(disc, b));
    double t0 = q / a, t1 = c / q;
    if (t0 > t1) std::swap(t0, t1);
    ASSERT_GT(t0, 0.0);
    all.clear();
    ASSERT_EQ(intersectBezierTriangleAll(piece, origin, d, 0.0, kInfinity, all), 2u) << i;
    std::sort(all.begin(), all.end(),
              [](const BezierHit& x, const BezierHit& y) { return x.t < y.t; });
    EXPECT_NEAR(all[0].t, t0, 1e-9 * t1);
    EXPECT_NEAR(all[1].t, t1, 1e-9 * t1);
    for (const BezierHit& h : all)
      EXPECT_NEAR((piece.position(h.u, h.v) - (origin + h.t * d)).norm(), 0.0, 1e-9);
    BezierHit hit;
    ASSERT_TRUE(intersectBezierTriangle(piece, origin, d, 0.0, kInfinity, hit));
    EXPECT_NEAR(hit.t, t0, 1e-9 * t1);
    const double between = 0.5 * (t0 + t1);
    ASSERT_TRUE(intersectBezierTriangle(piece, origin, d, between, kInfinity, hit));
    EXPECT_NEAR(hit.t, t1, 1e-9 * t1);
    all.clear();
    EXPECT_EQ(intersectBezierTriangleAll(piece, origin, d, between, kInfinity, all), 1u);
    EXPECT_FALSE(intersectBezierTriangle(piece, origin, d, 0.0, 0.999 * t0, hit));
  }
}

// A general quartic (every control point moved): the aimed-at point is among the hits.
TEST(BezierIntersect, CurvedQuarticReintersection) {
  Pcg32 rng(17);
  std::vector<BezierHit> all;
  int grazing = 0;
  for (int p = 0; p < 40; ++p) {
    BezierTriangle piece = bumpyPiece(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), 0.4, rng);
    for (Vec3& b : piece.b) b.head<2>() += 0.1 * Vec2(rng.nextDouble(), rng.nextDouble());
    for (int i = 0; i < 500; ++i) {
      const Vec2 uv = domainPoint(rng);
      const Vec3 target = piece.position(uv.x(), uv.y());
      const Vec3 origin = target + (0.3 + 2.0 * rng.nextDouble()) * uniformDirection(rng);
      const double distance = (target - origin).norm();
      const Vec3 d = (target - origin) / distance;
      all.clear();
      intersectBezierTriangleAll(piece, origin, d, 0.0, kInfinity, all);
      const auto match = std::find_if(all.begin(), all.end(), [&](const BezierHit& h) {
        return std::abs(h.u - uv.x()) < 1e-9 && std::abs(h.v - uv.y()) < 1e-9;
      });
      // A ray (nearly) tangent to the surface where it aims meets it in a double or triple
      // root, which no tracer resolves better than the square or cube root of the rounding
      // error (1e-5 in t for a triple root): the check below is for rays at least 1° off the
      // tangent plane.
      if (std::abs(d.dot(piece.normal(uv.x(), uv.y()))) < std::sin(M_PI / 180.0)) {
        ++grazing;
        continue;
      }
      ASSERT_NE(match, all.end()) << p << " " << i << ": aimed at (" << uv.x() << ", " << uv.y()
                                  << ") t " << distance << ", " << all.size() << " hits"
                                  << (all.empty() ? "" : ", first at (")
                                  << (all.empty() ? 0.0 : all[0].u) << ", "
                                  << (all.empty() ? 0.0 : all[0].v) << ") t "
                                  << (all.empty() ? 0.0 : all[0].t);
      EXPECT_NEAR(match->t, distance, 1e-9 * distance);
      for (const BezierHit& h : all)
        EXPECT_NEAR((piece.position(h.u, h.v) - (origin + h.t * d)).norm(), 0.0, 1e-9);
      BezierHit hit;
      ASSERT_TRUE(intersectBezierTriangle(piece, origin, d, 0.0, kInfinity, hit));
      EXPECT_LE(hit.t, distance * (1 + 1e-9));
    }
  }
  // Uniform directions lie within 1° of a plane with probability sin 1° = 1.75%.
  EXPECT_LT(grazing, 40 * 500 * 25 / 1000);
}

// 4 sub-triangles of a curved height field meeting exactly: rays aimed anywhere in the union,
// a quarter of them exactly at the shared edges and corners, hit exactly once.
TEST(BezierIntersect, SharedEdgesAreWatertight) {
  Pcg32 rng(21);
  const BezierTriangle parent =
      bumpyPiece(Vec3(-1, -1, 0), Vec3(1.5, -0.8, 0), Vec3(-0.6, 1.4, 0), 0.05, rng);
  const auto sub = fixtures::watertightSplit(parent);
  std::vector<BezierHit> all;
  std::vector<double> ts;
  int misses = 0, doubles = 0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    Vec2 uv = domainPoint(rng);
    switch (i % 8) {  // on the three shared edges, and the shared corners
      case 0: {
        const double s = rng.nextDouble();
        uv = Vec2(0.5 * s, 0.5 * (1.0 - s));
        break;
      }
      case 1:
        uv = Vec2(0.5 * rng.nextDouble(), 0.5);
        break;
      case 2:
        uv = Vec2(0.5, 0.5 * rng.nextDouble());
        break;
      case 3:
        uv = std::array<Vec2, 3>{Vec2(0.5, 0), Vec2(0, 0.5), Vec2(0.5, 0.5)}[i % 3];
        break;
      default:
        break;
    }
    const Vec3 target = parent.position(uv.x(), uv.y());
    const Vec3 d = downward(rng, 30.0);
    const Vec3 origin = target - (0.5 + rng.nextDouble()) * d;
    const double distance = (target - origin).norm();
    ts.clear();
    for (const BezierTriangle& piece : sub) {
      all.clear();
      intersectBezierTriangleAll(piece, origin, d, 0.0, kInfinity, all);
      for (const BezierHit& h : all) ts.push_back(h.t);
    }
    std::sort(ts.begin(), ts.end());
    size_t clusters = 0;
    for (size_t k = 0; k < ts.size(); ++k) clusters += k == 0 || ts[k] - ts[k - 1] > 1e-9;
    misses += clusters == 0;
    doubles += clusters > 1;
    if (clusters == 1) {
      EXPECT_NEAR(ts.front(), distance, 1e-9 * distance);
      EXPECT_NEAR(ts.back(), distance, 1e-9 * distance);
    }
  }
  EXPECT_EQ(misses, 0);
  EXPECT_EQ(doubles, 0);
}

// Pieces collapsed to a point or a segment: rays through them end (a node budget bounds the
// work) and report nothing off the ray.
TEST(BezierIntersect, DegeneratePiecesAreCheap) {
  BezierTriangle point;
  point.b.fill(Vec3(0.5, 0.25, 1.0));
  const BezierTriangle segment = flatPiece(Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(0.5, 0.5, 0.5));
  Pcg32 rng(29);
  std::vector<BezierHit> all;
  // The node budget bounds the work (an all-hits query on the segment visits up to 200,000
  // nodes); what is checked here is that what comes back lies on the ray and the piece.
  for (int i = 0; i < fixtures::samples(40); ++i) {
    const Vec3 d = uniformDirection(rng);
    for (const BezierTriangle* piece : std::array<const BezierTriangle*, 2>{&point, &segment}) {
      const Vec3 on = piece == &point ? point.b[0] : Vec3::Constant(rng.nextDouble());
      const Vec3 origin = on - 2.0 * d;
      BezierHit hit;
      if (intersectBezierTriangle(*piece, origin, d, 0.0, kInfinity, hit)) {
        EXPECT_NEAR((piece->position(hit.u, hit.v) - (origin + hit.t * d)).norm(), 0.0, 1e-6);
      }
      all.clear();
      intersectBezierTriangleAll(*piece, origin, d, 0.0, kInfinity, all);
      EXPECT_LE(all.size(), 16u);
    }
  }
}

}  // namespace
}  // namespace quadtri
