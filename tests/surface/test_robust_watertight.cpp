// The convex cells of the robust implicit model: polytopes, exact bounds of a quadric in them.
#include <gtest/gtest.h>

#include <map>
#include <random>

#include "quadtri/analysis/crack_rate.h"
#include "quadtri/geometry/accel.h"
#include "quadtri/geometry/model_geometry.h"
#include "quadtri/geometry/rng.h"
#include "quadtri/mesh/normals.h"
#include "quadtri/mesh/shapes.h"
#include "quadtri/mesh/topology.h"
#include "quadtri/surface/robust_cell.h"
#include "quadtri/surface/robust_implicit_model.h"

namespace quadtri {
namespace {

Vec4 plane(const Vec3& n, double d) {
  return Vec4(n.x(), n.y(), n.z(), d);
}

// A box cell lo <= x <= hi.
ConvexCell boxCell(const Vec3& lo, const Vec3& hi) {
  std::vector<Vec4> planes;
  for (int axis = 0; axis < 3; ++axis) {
    planes.push_back(plane(Vec3::Unit(axis), -lo[axis]));
    planes.push_back(plane(-Vec3::Unit(axis), hi[axis]));
  }
  return makeConvexCell(planes, 1e-12);
}

TEST(ConvexCell, TriangularPrismHasItsSixVerticesAndFiveFaces) {
  const std::vector<Vec4> planes = {plane(Vec3(1, 0, 0), 0), plane(Vec3(0, 1, 0), 0),
                                    plane(Vec3(-1, -1, 0).normalized(), std::sqrt(0.5)),
                                    plane(Vec3(0, 0, 1), 1), plane(Vec3(0, 0, -1), 2)};
  const ConvexCell cell = makeConvexCell(planes, 1e-12);
  ASSERT_EQ(cell.vertices.size(), 6u);
  const std::vector<size_t> faceSizes = {4, 4, 4, 3, 3};
  for (size_t f = 0; f < 5; ++f) EXPECT_EQ(cell.faces[f].size(), faceSizes[f]) << f;
  const Bounds3 b = cell.bounds();
  EXPECT_LT((b.lo - Vec3(0, 0, -1)).norm(), 1e-15);
  EXPECT_LT((b.hi - Vec3(1, 1, 2)).norm(), 1e-15);
  // A sixth plane that misses the prism leaves it unchanged; one that cuts a corner adds one.
  std::vector<Vec4> more = planes;
  more.push_back(plane(Vec3(0, 0, -1), 5));
  EXPECT_EQ(makeConvexCell(more, 1e-12).vertices.size(), 6u);
  more.back() = plane(Vec3(-1, 0, 0), 0.5);  // x <= 0.5
  EXPECT_EQ(makeConvexCell(more, 1e-12).vertices.size(), 8u);
}

TEST(ConvexCell, QuadricBoundsAreTheExactBoxOfTheClippedSurface) {
  // The cap z >= 1/2 of the unit sphere: |x|, |y| <= √(3/4) on its rim, z in [1/2, 1].
  const QuadricCoeffs sphere = {1, 1, 1, 0, 0, 0, 0, 0, 0, -1};
  Bounds3 b = quadricBoundsInCell(sphere, boxCell(Vec3(-2, -2, 0.5), Vec3(2, 2, 2)));
  const double r = std::sqrt(0.75);
  EXPECT_NEAR(b.lo.x(), -r, 1e-15);
  EXPECT_NEAR(b.hi.y(), r, 1e-15);
  EXPECT_NEAR(b.lo.z(), 0.5, 1e-15);
  EXPECT_NEAR(b.hi.z(), 1.0, 1e-15);
  // x²/4 + y² + 4z² = 1 for z >= 1/4: the rim x = ±2√(3/4), y = ±√(3/4); the top z = 1/2.
  const QuadricCoeffs ellipsoid = {0.25, 1, 4, 0, 0, 0, 0, 0, 0, -1};
  b = quadricBoundsInCell(ellipsoid, boxCell(Vec3(-3, -3, 0.25), Vec3(3, 3, 3)));
  EXPECT_NEAR(b.hi.x(), 2 * r, 1e-15);
  EXPECT_NEAR(b.lo.y(), -r, 1e-15);
  EXPECT_NEAR(b.lo.z(), 0.25, 1e-15);
  EXPECT_NEAR(b.hi.z(), 0.5, 1e-15);
  // Clipped by the cell's sides too: |x| <= 1 cuts the rim; the extreme in y is then inside.
  b = quadricBoundsInCell(ellipsoid, boxCell(Vec3(-1, -3, 0.25), Vec3(1, 3, 3)));
  EXPECT_NEAR(b.hi.x(), 1.0, 1e-15);
  EXPECT_NEAR(b.hi.y(), r, 1e-15);
  // A cell the surface misses.
  EXPECT_TRUE(quadricBoundsInCell(sphere, boxCell(Vec3(2, 2, 2), Vec3(3, 3, 3))).empty());
}

TEST(ConvexCell, BetweenBoundsOnAFaceAreTheExactBoxOfTheRegion) {
  // Face y = 0 of [-1,1]×[0,1]×[-1,1]; the circle x² + (z+1)² = 9/4 on it and the base z = 0:
  // where the sphere says inside and the base outside, |x| <= 1 (the face's sides) and
  // 0 <= z <= 1/2 (the circle's top).
  const ConvexCell cell = boxCell(Vec3(-1, 0, -1), Vec3(1, 1, 1));
  const QuadricCoeffs sphere = {1, 1, 1, 0, 0, 0, 0, 0, 2, 1 - 2.25};
  const int face = 2;  // y >= 0
  ASSERT_EQ(cell.planes[face], plane(Vec3(0, 1, 0), 0));
  const Bounds3 b = betweenBoundsOnFace(sphere, 1.0, plane(Vec3(0, 0, 1), 0), cell, face);
  EXPECT_NEAR(b.lo.x(), -1.0, 1e-15);
  EXPECT_NEAR(b.hi.x(), 1.0, 1e-15);
  EXPECT_NEAR(b.lo.z(), 0.0, 1e-15);
  EXPECT_NEAR(b.hi.z(), 0.5, 1e-15);
  EXPECT_EQ(b.lo.y(), 0.0);
  EXPECT_EQ(b.hi.y(), 0.0);
  // A base above the whole face: the region is the face's part of the disc, down to the
  // face's lower side z = -1.
  const Bounds3 c = betweenBoundsOnFace(sphere, 1.0, plane(Vec3(0, 0, -1), 5), cell, face);
  EXPECT_NEAR(c.lo.z(), -1.0, 1e-15);
  EXPECT_NEAR(c.hi.z(), 0.5, 1e-15);
  EXPECT_NEAR(c.lo.x(), -1.0, 1e-15);
  // The sphere's inside with the base's below everywhere: nothing between them.
  EXPECT_TRUE(betweenBoundsOnFace(QuadricCoeffs{0, 0, 0, 0, 0, 0, 0, 0, 0, -1}, 1.0,
                                  plane(Vec3(0, 0, -1), -5), cell, face)
                  .empty());
}

}  // namespace
}  // namespace quadtri
