// Long quadric patches traced as parts with tighter boxes (quadric_patch_parts.h): the parts
// hold every point of their patch, and an Accel that traces them finds the hits an Accel that
// traces whole patches finds, exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "fixtures/tight_bounds.h"
#include "fixtures/twisted_band.h"
#include "quadtri/geometry/accel.h"
#include "quadtri/geometry/rng.h"
#include "quadtri/mesh/shapes.h"
#include "quadtri/surface/implicit_model.h"
#include "quadtri/surface/quadric_patch_parts.h"
#include "quadtri/surface/robust_implicit_model.h"

namespace quadtri {
namespace {

using fixtures::expectExactBoxesChangeNoHit;
using fixtures::twistedBand;

// A ray from outside the band's box towards a random point near the band.
Ray randomRay(Pcg32& rng, double height) {
  const auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * rng.nextDouble(); };
  const double a = uniform(0.0, 2.0 * kPi), r = uniform(3.0, 4.0);
  const Vec3 origin(r * std::cos(a), r * std::sin(a), uniform(-1.0, height + 1.0));
  const double b = uniform(0.0, 2.0 * kPi), s = uniform(0.7, 1.3);
  const Vec3 target(s * std::cos(b), s * std::sin(b), uniform(0.0, height));
  return {origin, (target - origin).normalized()};
}

TEST(QuadricPatchParts, QuadricBoundsInABoxHoldTheQuadricThereAndNoMore) {
  // The unit sphere x² + y² + z² − 1 in the box [0.5, 2] × [-2, 2] × [-2, 2]: the cap x ≥ 0.5,
  // whose bounds are x in [0.5, 1], y and z in [-√0.75, √0.75].
  const QuadricCoeffs sphere = {1, 1, 1, 0, 0, 0, 0, 0, 0, -1};
  Bounds3 box;
  box.lo = Vec3(0.5, -2, -2);
  box.hi = Vec3(2, 2, 2);
  const Bounds3 cap = quadricBoundsInBox(sphere, box);
  const double r = std::sqrt(0.75);
  // Exact but for the margin kept for the roots' rounding: 1e-3 of the box's side (4).
  constexpr double kMargin = 4e-3 + 1e-8;
  EXPECT_NEAR(cap.lo.x(), 0.5, 1e-8);  // the box's own face
  EXPECT_NEAR(cap.hi.x(), 1.0, kMargin);
  EXPECT_GE(cap.hi.x(), 1.0);
  for (int c = 1; c < 3; ++c) {
    EXPECT_NEAR(cap.lo[c], -r, kMargin);
    EXPECT_NEAR(cap.hi[c], r, kMargin);
    EXPECT_LE(cap.lo[c], -r);
    EXPECT_GE(cap.hi[c], r);
  }
  // Every point of the cap lies inside.
  Pcg32 rng(3);
  for (int i = 0; i < 2000; ++i) {
    const double theta = std::acos(0.5 + 0.5 * rng.nextDouble()), phi = 2 * kPi * rng.nextDouble();
    const Vec3 p(std::cos(theta), std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi));
    EXPECT_TRUE(cap.contains(p)) << p.transpose();
  }
  // A box the sphere does not reach holds none of it.
  box.lo = Vec3(1.5, -2, -2);
  EXPECT_TRUE(quadricBoundsInBox(sphere, box).empty());
}

TEST(QuadricPatchParts, ExactBoxesKeepEveryHitOfTheirPatch) {
  ShapeParams params;
  params.level = 2;
  const auto sphere = std::make_shared<TriangleMesh>(makeBuiltin("icosphere", params).mesh);
  expectExactBoxesChangeNoHit(sphere, 0.03);
  // Small, seen from far away: 10⁵ patch sizes.
  auto small = std::make_shared<TriangleMesh>(*sphere);
  for (Vec3& p : small->positions) p *= 1e-3;
  expectExactBoxesChangeNoHit(small, 0.03, 1e5);
  expectExactBoxesChangeNoHit(std::make_shared<TriangleMesh>(twistedBand(24, 6, 3.0)), 0.03);
  // Normals tilted at random: ellipsoids, hyperboloids and cylinders.
  auto tilted = std::make_shared<TriangleMesh>(*sphere);
  Pcg32 rng(23);
  for (Vec3& n : tilted->normals)
    n = (n + 0.4 * Vec3(rng.nextDouble() - 0.5, rng.nextDouble() - 0.5, rng.nextDouble() - 0.5))
            .normalized();
  expectExactBoxesChangeNoHit(tilted, 0.03);
  // A fine mesh: the thesis' plane (4) nearly faces plane (1), so every cell is thin (0.5% of
  // its side across) and the patch keeps the cell's box, not the sampled one, which is 5% of
  // the longest edge larger on every side. Their total area against the triangles' own boxes:
  // 1.11 (the sampled boxes' 1.32).
  params.level = 5;
  const auto fine = std::make_shared<TriangleMesh>(makeBuiltin("icosphere", params).mesh);
  expectExactBoxesChangeNoHit(fine, 0.1, 1000.0, 20);
  {
    const ImplicitModel model(fine);
    double boxes = 0.0, triangles = 0.0;
    for (size_t t = 0; t < fine->triangleCount(); ++t) {
      Bounds3 triangle;
      for (int k = 0; k < 3; ++k) triangle.extend(fine->corner(t, k));
      triangles += triangle.surfaceArea();
      boxes += model.renderPatches()[t].bounds.surfaceArea();
    }
    EXPECT_LT(boxes, 1.15 * triangles);
  }
  // Flat faces: each patch is its triangle's plane, inside planes that all hold the face's
  // normal (the cell is open along it until the box's slab closes it), and its box is the
  // triangle's own.
  params.divisions = 3;
  const auto cube = std::make_shared<TriangleMesh>(makeBuiltin("cube", params).mesh);
  expectExactBoxesChangeNoHit(cube, 0.3);
  const ImplicitModel flat(cube);
  for (size_t t = 0; t < cube->triangleCount(); ++t) {
    Bounds3 triangle;
    for (int k = 0; k < 3; ++k) triangle.extend(cube->corner(t, k));
    const Bounds3& box = flat.renderPatches()[t].bounds;
    // Its triangle's box, grown by the margin for the roots' rounding (1e-3 of the sampled
    // box's side, under 1e-3 here), where the sampled box had 5% of the longest edge.
    EXPECT_LT((box.lo - triangle.lo).cwiseAbs().maxCoeff(), 1e-3) << "triangle " << t;
    EXPECT_LT((box.hi - triangle.hi).cwiseAbs().maxCoeff(), 1e-3) << "triangle " << t;
  }
}

TEST(QuadricPatchParts, WellShapedMeshesKeepTheirPatchesWhole) {
  ShapeParams params;
  params.level = 3;
  const auto mesh = std::make_shared<TriangleMesh>(makeBuiltin("icosphere", params).mesh);
  const ImplicitModel model(mesh);
  EXPECT_TRUE(quadricPatchParts(model.renderPatches(), *mesh).empty());
}

// Slivers are split; each part's box lies in its patch's, the parts are fewer per patch than
// the cap allows and shrink the boxes' total area; every point of a patch (found by rays
// against the whole patch) lies in one of its parts.
void expectPartsHoldTheirPatches(const SurfaceModel& model, bool bridges) {
  const std::vector<QuadricPatch>& patches = model.renderPatches();
  const std::vector<QuadricPatchPart> parts = quadricPatchParts(patches, model.mesh());
  ASSERT_FALSE(parts.empty());
  ASSERT_GT(parts.size(), patches.size());
  std::vector<std::vector<Bounds3>> partsOf(patches.size());
  double whole = 0.0, split = 0.0;
  for (const QuadricPatchPart& part : parts) {
    ASSERT_LT(part.patch, patches.size());
    const Bounds3 box = part.bounds();
    const Bounds3& patchBox = patches[part.patch].bounds;
    EXPECT_TRUE((box.lo.array() >= patchBox.lo.array() - 1e-6).all() &&
                (box.hi.array() <= patchBox.hi.array() + 1e-6).all());
    partsOf[part.patch].push_back(box);
    split += box.surfaceArea();
  }
  size_t splitBridges = 0;
  for (size_t i = 0; i < patches.size(); ++i) {
    ASSERT_GE(partsOf[i].size(), 1u) << "patch " << i;
    ASSERT_LE(partsOf[i].size(), size_t(1) << kMaxPartDepth) << "patch " << i;
    whole += patches[i].bounds.surfaceArea();
    splitBridges += patches[i].isBridge() && partsOf[i].size() > 1;
  }
  // The robust model's bridges lie along the slivers' long edges: they are split too.
  if (bridges) {
    EXPECT_GT(splitBridges, 0u);
  }
  EXPECT_LT(split, kMeshSplitGain * whole);
  Pcg32 rng(11);
  int hits = 0;
  for (int i = 0; i < 20000; ++i) {
    const Ray ray = randomRay(rng, 3.0);
    for (size_t p = 0; p < patches.size(); ++p) {
      double t;
      if (!intersectPrimitive(patches, p, ray.origin, ray.direction, 0.0, kInfinity, t)) continue;
      ++hits;
      const Vec3 point = ray.origin + t * ray.direction;
      bool held = false;
      for (const Bounds3& box : partsOf[p]) held = held || box.contains(point);
      ASSERT_TRUE(held) << "patch " << p << " point " << point.transpose();
    }
  }
  EXPECT_GT(hits, 1000);
}

TEST(QuadricPatchParts, SliversSplitIntoPartsThatHoldEveryPointOfThem) {
  const auto mesh = std::make_shared<TriangleMesh>(twistedBand(24, 6, 3.0));
  expectPartsHoldTheirPatches(ImplicitModel(mesh), false);
}

TEST(QuadricPatchParts, RobustSliversSplitIntoPartsThatHoldEveryPointOfThem) {
  // Tilted normals: the patches disagree along the edges, and bridges join them.
  const auto mesh = std::make_shared<TriangleMesh>(twistedBand(24, 6, 3.0, 0.3));
  expectPartsHoldTheirPatches(RobustImplicitModel(mesh), true);
}

// The same rays through an Accel that traces parts and one that traces whole patches (no mesh
// given): the same nearest hits, to the bit, and the same occlusion.
void expectPartsChangeNoHit(const SurfaceModel& model) {
  const std::vector<QuadricPatch>& patches = model.renderPatches();
  Accel whole, parts;
  const uint32_t wholeId = whole.addQuadricPatches(patches);
  const uint32_t partsId = parts.addQuadricPatches(patches, &model.mesh());
  whole.commit();
  parts.commit();
  EXPECT_EQ(whole.patchPartBytes(), 0u);
  EXPECT_GT(parts.patchPartBytes(), 0u);
  EXPECT_GT(parts.geometryBytes(), whole.geometryBytes());
  Pcg32 rng(5);
  int hits = 0;
  for (int i = 0; i < 20000; ++i) {
    Ray ray = randomRay(rng, 3.0);
    const RayHit a = whole.intersect(ray), b = parts.intersect(ray);
    ASSERT_EQ(a.valid(), b.valid()) << "ray " << i;
    EXPECT_EQ(whole.occluded(ray), parts.occluded(ray)) << "ray " << i;
    if (!a.valid()) continue;
    ++hits;
    ASSERT_EQ(a.geometry, wholeId);
    ASSERT_EQ(b.geometry, partsId);
    EXPECT_EQ(a.t, b.t) << "ray " << i;
    EXPECT_EQ(a.primitive, b.primitive) << "ray " << i;
    EXPECT_EQ(a.geometricNormal, b.geometricNormal) << "ray " << i;
    // From the hit on: the next hit, as a path tracer's next segment would find it.
    ray.tnear = a.t * (1.0 + 1e-9);
    const RayHit a2 = whole.intersect(ray), b2 = parts.intersect(ray);
    ASSERT_EQ(a2.valid(), b2.valid()) << "ray " << i;
    if (a2.valid()) {
      EXPECT_EQ(a2.t, b2.t) << "ray " << i;
    }
  }
  EXPECT_GT(hits, 5000);
}

TEST(QuadricPatchParts, AnAccelOfPartsFindsTheHitsOfWholePatches) {
  const auto mesh = std::make_shared<TriangleMesh>(twistedBand(24, 6, 3.0));
  expectPartsChangeNoHit(ImplicitModel(mesh));
}

TEST(QuadricPatchParts, RobustAccelOfPartsFindsTheHitsOfWholePatches) {
  const auto mesh = std::make_shared<TriangleMesh>(twistedBand(24, 6, 3.0, 0.3));
  expectPartsChangeNoHit(RobustImplicitModel(mesh));
}

TEST(QuadricPatchParts, CollectingEveryHitTracesPatchesWhole) {
  const auto mesh = std::make_shared<TriangleMesh>(twistedBand(24, 6, 3.0));
  const ImplicitModel model(mesh);
  Accel::Options options;
  options.collectHits = true;
  Accel accel(options);
  accel.addQuadricPatches(model.renderPatches(), mesh.get());
  accel.commit();
  EXPECT_EQ(accel.patchPartBytes(), 0u);
}

}  // namespace
}  // namespace quadtri
