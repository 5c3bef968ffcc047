#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "fixtures/sphere_patches.h"
#include "quadtri/geometry/accel.h"
#include "quadtri/geometry/rng.h"
#include "quadtri/math/error.h"
#include "quadtri/mesh/shapes.h"
#include "quadtri/surface/g1_model.h"

namespace quadtri {
namespace {

TriangleMesh icosphere(int level) {
  ShapeParams p;
  p.level = level;
  return makeBuiltin("icosphere", p).mesh;
}

using fixtures::spherePatches;

TEST(Accel, TriangleHitAtAnalyticT) {
  const FlushToZeroScope flushToZero;
  TriangleMesh mesh;
  mesh.positions = {Vec3(-1, -1, 2), Vec3(3, -1, 2), Vec3(-1, 3, 2)};
  mesh.triangles = {{0, 1, 2}};
  Accel accel;
  const uint32_t id = accel.addTriangles(mesh);
  accel.commit();
  EXPECT_EQ(accel.geometryBytes(), size_t(4 * 12));
  Pcg32 rng(7);
  for (int i = 0; i < 200; ++i) {
    const Vec3 origin(rng.nextDouble() - 0.5, rng.nextDouble() - 0.5, -rng.nextDouble());
    double b1 = rng.nextDouble(), b2 = rng.nextDouble();
    if (b1 + b2 > 1) b1 = 1 - b1, b2 = 1 - b2;
    const Vec3 target =
        (1 - b1 - b2) * mesh.positions[0] + b1 * mesh.positions[1] + b2 * mesh.positions[2];
    const double distance = (target - origin).norm();
    const Ray ray{origin, (target - origin) / distance};
    const RayHit hit = accel.intersect(ray);
    ASSERT_TRUE(hit.valid());
    EXPECT_EQ(hit.geometry, id);
    EXPECT_EQ(hit.primitive, 0u);
    EXPECT_NEAR(hit.t, distance, 1e-6 * distance);
    EXPECT_NEAR(hit.u, b1, 1e-5);
    EXPECT_NEAR(hit.v, b2, 1e-5);
    EXPECT_NEAR((hit.geometricNormal - Vec3(0, 0, 1)).norm(), 0.0, 1e-7);
    EXPECT_FALSE(accel.occluded({ray.origin, ray.direction, 0.0, 0.99 * distance}));
    EXPECT_TRUE(accel.occluded({ray.origin, ray.direction, 0.0, 1.01 * distance}));
    EXPECT_FALSE(accel.intersect({ray.origin, -ray.direction}).valid());
  }
}

// HitNormal::Skip leaves the normal of triangle and patch hits zero and changes nothing else:
// the same hit, t, (u, v) and point as with the normal filled, which is unit.
TEST(Accel, SkippingTheHitNormalChangesNothingElse) {
  const FlushToZeroScope flushToZero;
  TriangleMesh mesh = icosphere(2);
  for (Vec3& p : mesh.positions) p = 0.5 * p + Vec3(2.0, 0.0, 0.0);
  const std::vector<QuadricPatch> patches = spherePatches();
  Accel accel;
  const uint32_t triangles = accel.addTriangles(mesh);
  const uint32_t quadrics = accel.addQuadricPatches(patches);
  accel.commit();
  Pcg32 rng(23);
  int hitTriangles = 0, hitPatches = 0;
  for (int i = 0; i < 4000; ++i) {
    const Vec3 origin(1.0, 0.0, 3.0);
    const Vec3 target(4.0 * rng.nextDouble() - 1.5, 2.0 * rng.nextDouble() - 1.0,
                      2.0 * rng.nextDouble() - 1.0);
    const Ray ray{origin, (target - origin).normalized()};
    const RayHit filled = accel.intersect(ray);
    const RayHit skipped = accel.intersect(ray, Accel::HitNormal::Skip);
    ASSERT_EQ(filled.valid(), skipped.valid());
    if (!filled.valid()) continue;
    hitTriangles += filled.geometry == triangles;
    hitPatches += filled.geometry == quadrics;
    EXPECT_EQ(skipped.geometry, filled.geometry);
    EXPECT_EQ(skipped.primitive, filled.primitive);
    EXPECT_EQ(skipped.t, filled.t);
    EXPECT_EQ(skipped.u, filled.u);
    EXPECT_EQ(skipped.v, filled.v);
    EXPECT_EQ(skipped.point, filled.point);
    EXPECT_EQ(skipped.geometricNormal, Vec3::Zero());
    EXPECT_NEAR(filled.geometricNormal.norm(), 1.0, 1e-12);
  }
  EXPECT_GT(hitTriangles, 200);
  EXPECT_GT(hitPatches, 200);
}

TEST(Accel, RobustRaysThroughSharedEdgesAndVerticesNeverMiss) {
  const FlushToZeroScope flushToZero;
  for (int level = 0; level <= 3; ++level) {
    const TriangleMesh mesh = icosphere(level);
    Accel accel(Accel::Options{true, false});
    accel.addTriangles(mesh);
    accel.commit();
    std::vector<Vec3> targets = mesh.positions;
    for (size_t t = 0; t < mesh.triangleCount(); ++t)
      for (int k = 0; k < 3; ++k)
        for (const double s : {0.5, 1.0 / 3.0, 1e-4})
          targets.push_back((1 - s) * mesh.corner(t, k) + s * mesh.corner(t, (k + 1) % 3));
    size_t missed = 0;
    for (const Vec3& target : targets) {
      const RayHit hit = accel.intersect({Vec3::Zero(), target.normalized()});
      if (!hit.valid())
        ++missed;
      else
        EXPECT_NEAR(hit.t, target.norm(), 1e-6) << "level " << level;
    }
    EXPECT_EQ(missed, 0u) << "level " << level << ", " << targets.size() << " rays";
  }
}

TEST(Accel, QuadricSpherePatchesHitAtUnitDistanceWithRadialNormal) {
  const FlushToZeroScope flushToZero;
  const std::vector<QuadricPatch> patches = spherePatches();
  Accel accel;
  const uint32_t id = accel.addQuadricPatches(patches);
  accel.commit();
  EXPECT_EQ(accel.geometryBytes(), patches.size() * sizeof(QuadricPatch));
  Pcg32 rng(11);
  std::vector<Vec3> directions;
  for (int i = 0; i < 5000; ++i) directions.push_back(uniformDirection(rng));
  // Patch boundaries: the icosahedron's vertices and points of its edges, on the sphere.
  const TriangleMesh ico = makeBuiltin("icosahedron").mesh;
  for (size_t t = 0; t < ico.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k)
      for (const double s : {0.0, 0.5, 0.25})
        directions.push_back(
            ((1 - s) * ico.corner(t, k) + s * ico.corner(t, (k + 1) % 3)).normalized());
  for (const Vec3& d : directions) {
    const RayHit hit = accel.intersect({Vec3::Zero(), d});
    ASSERT_TRUE(hit.valid()) << d.transpose();
    EXPECT_EQ(hit.geometry, id);
    EXPECT_NEAR(hit.t, 1.0, 1e-9);
    EXPECT_NEAR((hit.geometricNormal - d).norm(), 0.0, 1e-9);
    EXPECT_TRUE(patches[hit.primitive].inside(hit.t * d));
    EXPECT_TRUE(accel.occluded({Vec3::Zero(), d, 0.0, 1.0 + 1e-6}));
    EXPECT_FALSE(accel.occluded({Vec3::Zero(), d, 0.0, 1.0 - 1e-6}));
  }
}

// A mesh far from the world origin is traced in floats relative to its own centre
// (Accel::origin), as finely as the same mesh around the origin: the same rays meet both at the
// same t to float precision of the mesh's size, not of its distance from the origin (a float
// ulp at 1e6 is 0.0625). A mesh around the origin keeps the world origin.
TEST(Accel, FarFromTheOriginTracesAsFinelyAsNearIt) {
  const FlushToZeroScope flushToZero;
  const TriangleMesh near = icosphere(3);
  const Vec3 offset(1e6, -3e6, 5e5);
  TriangleMesh far = near;
  for (Vec3& x : far.positions) x += offset;
  Accel nearAccel, farAccel;
  nearAccel.addTriangles(near);
  farAccel.addTriangles(far);
  nearAccel.commit();
  farAccel.commit();
  EXPECT_EQ(nearAccel.origin(), Vec3::Zero());
  EXPECT_LT((farAccel.origin() - offset).cwiseAbs().maxCoeff(), 1e-9);
  // The box in world coordinates: the mesh's to within float rounding of its size.
  const Bounds3 box = farAccel.bounds(), meshBox = far.bounds();
  EXPECT_LT(std::max((box.lo - meshBox.lo).cwiseAbs().maxCoeff(),
                     (box.hi - meshBox.hi).cwiseAbs().maxCoeff()),
            1e-6);
  Pcg32 rng(5);
  int hits = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 from = 3.0 * uniformDirection(rng), to = 0.5 * uniformDirection(rng);
    const Vec3 d = (to - from).normalized();
    const RayHit a = nearAccel.intersect({from, d});
    const RayHit b = farAccel.intersect({from + offset, d});
    ASSERT_EQ(a.valid(), b.valid()) << i;
    if (!a.valid()) continue;
    ++hits;
    EXPECT_NEAR(a.t, b.t, 1e-6) << i;
    EXPECT_NEAR((a.geometricNormal - b.geometricNormal).norm(), 0.0, 1e-5) << i;
    EXPECT_TRUE(farAccel.occluded({from + offset, d, 0.0, b.t + 1e-5}));
    EXPECT_FALSE(farAccel.occluded({from + offset, d, 0.0, b.t - 1e-5}));
  }
  EXPECT_EQ(hits, 2000);
}

// Quadric patches far from the origin get boxes grown for float error relative to their own
// centre (1e-5 of their size), not of their distance from the origin, where 1e-5 of 1e6 would
// put every patch's box around every other's.
TEST(Accel, PatchBoxesFarFromTheOriginStayTight) {
  const FlushToZeroScope flushToZero;
  const Vec3 c(1e6, 1e6, 0.0);
  std::vector<QuadricPatch> patches = spherePatches();
  for (QuadricPatch& patch : patches) {
    // |x − c|² − 1 and planes n·(x − c) >= 0.
    patch.q = {1, 1, 1, 0, 0, 0, -2 * c.x(), -2 * c.y(), -2 * c.z(), c.squaredNorm() - 1.0};
    for (int k = 0; k < patch.planeCount; ++k)
      patch.planes[size_t(k)][3] = -patch.planes[size_t(k)].head<3>().dot(c);
    patch.bounds.lo += c;
    patch.bounds.hi += c;
  }
  Accel accel;
  accel.addQuadricPatches(patches);
  accel.commit();
  const Bounds3 box = accel.bounds();
  // The patches' own boxes reach 1e-3 beyond the sphere (the fixture's inflation).
  EXPECT_LT(std::max((box.lo - (c - Vec3::Ones())).cwiseAbs().maxCoeff(),
                     (box.hi - (c + Vec3::Ones())).cwiseAbs().maxCoeff()),
            2e-3);
  Pcg32 rng(3);
  for (int i = 0; i < 500; ++i) {
    const Vec3 d = uniformDirection(rng);
    const RayHit hit = accel.intersect({c, d});
    ASSERT_TRUE(hit.valid()) << d.transpose();
    // The quadric's terms are 1e12 here and cancel: its roots are known to about 1e-4.
    EXPECT_NEAR(hit.t, 1.0, 1e-3);
  }
}

TEST(Accel, NearestOfTrianglesAndPatches) {
  // A unit sphere of patches cut by the plane z = 0.5 (two big triangles): rays from the
  // centre hit the plane first where it is nearer than the sphere, and the sphere elsewhere.
  const FlushToZeroScope flushToZero;
  const std::vector<QuadricPatch> patches = spherePatches();
  TriangleMesh plane;
  plane.positions = {Vec3(-3, -3, 0.5), Vec3(3, -3, 0.5), Vec3(3, 3, 0.5), Vec3(-3, 3, 0.5)};
  plane.triangles = {{0, 1, 2}, {0, 2, 3}};
  Accel accel;
  const uint32_t sphereId = accel.addQuadricPatches(patches);
  const uint32_t planeId = accel.addTriangles(plane);
  accel.commit();
  Pcg32 rng(5);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 d = uniformDirection(rng);
    const RayHit hit = accel.intersect({Vec3::Zero(), d});
    ASSERT_TRUE(hit.valid());
    if (d.z() > 0.5) {
      EXPECT_EQ(hit.geometry, planeId);
      EXPECT_NEAR(hit.t, 0.5 / d.z(), 1e-6);
    } else {
      EXPECT_EQ(hit.geometry, sphereId);
      EXPECT_NEAR(hit.t, 1.0, 1e-9);
    }
  }
}

// Accel keeps native triangles and user geometry in two Embree scenes, and a ray enters the
// user scene only where it meets that scene's bounds before its nearest triangle hit. Against
// the nearest hit over every primitive (the patches through the test the callbacks run, the
// triangles by Möller–Trumbore in double), for rays from everywhere: inside and outside the
// bounds, along the axes (zero direction components), from the planes of the bounds' faces,
// with the wall in front of or behind the sphere, and with shortened intervals. Geometry ids
// run over both scenes in the order the geometries were added.
TEST(Accel, SkippingTheUserSceneLosesNoHit) {
  const FlushToZeroScope flushToZero;
  const std::vector<QuadricPatch> patches = spherePatches();
  TriangleMesh wall, chip;
  wall.positions = {Vec3(-3, -3, 1.5), Vec3(3, -3, 1.5), Vec3(3, 3, 1.5), Vec3(-3, 3, 1.5)};
  wall.triangles = {{0, 1, 2}, {0, 2, 3}};
  chip.positions = {Vec3(-0.5, -0.5, -0.25), Vec3(0.5, -0.5, -0.25), Vec3(0, 0.5, -0.25)};
  chip.triangles = {{0, 1, 2}};
  Accel accel;
  ASSERT_EQ(accel.addTriangles(wall), 0u);
  ASSERT_EQ(accel.addQuadricPatches(patches), 1u);
  ASSERT_EQ(accel.addTriangles(chip), 2u);
  accel.commit();
  struct Expected {
    double t = kInfinity;
    uint32_t geometry = ~0u;
  };
  const auto triangleT = [](const TriangleMesh& mesh, size_t t, const Ray& ray) {
    const Vec3 a = mesh.corner(t, 0), e1 = mesh.corner(t, 1) - a, e2 = mesh.corner(t, 2) - a;
    const Vec3 p = ray.direction.cross(e2);
    const double det = e1.dot(p);
    if (det == 0.0) return kInfinity;
    const Vec3 s = ray.origin - a, q = s.cross(e1);
    const double u = s.dot(p) / det, v = ray.direction.dot(q) / det, hit = e2.dot(q) / det;
    return u >= 0 && v >= 0 && u + v <= 1 && hit > ray.tnear && hit < ray.tfar ? hit : kInfinity;
  };
  const auto nearest = [&](const Ray& ray) {
    Expected e;
    for (const auto& [mesh, id] : {std::pair{&wall, 0u}, std::pair{&chip, 2u}})
      for (size_t t = 0; t < mesh->triangleCount(); ++t)
        if (const double hit = triangleT(*mesh, t, ray); hit < e.t) e = {hit, id};
    for (size_t i = 0; i < patches.size(); ++i) {
      double hit;
      if (intersectPrimitive(patches, i, ray.origin, ray.direction, ray.tnear,
                             std::min(ray.tfar, e.t), hit) &&
          hit < e.t)
        e = {hit, 1u};
    }
    return e;
  };
  Pcg32 rng(29);
  const Vec3 axes[] = {Vec3::UnitX(),  Vec3::UnitY(),  Vec3::UnitZ(),
                       -Vec3::UnitX(), -Vec3::UnitY(), -Vec3::UnitZ()};
  int hitsOnSphere = 0, missesOfTheBounds = 0;
  for (int i = 0; i < 20000; ++i) {
    Ray ray;
    // Origins on a grid of quarter steps half the time: on the bounds' face planes (the
    // sphere's box is [-1, 1]³, grown) and on the wall's and chip's planes.
    for (int a = 0; a < 3; ++a)
      ray.origin[a] =
          i % 2 ? 0.25 * std::floor(16 * rng.nextDouble() - 8) : 6 * rng.nextDouble() - 3;
    ray.direction = i % 3 == 0 ? axes[rng.nextUint() % 6] : uniformDirection(rng);
    if (i % 5 == 0) ray.tnear = 0.5 * rng.nextDouble();
    if (i % 7 == 0) ray.tfar = 3 * rng.nextDouble();
    const Expected e = nearest(ray);
    const RayHit hit = accel.intersect(ray);
    ASSERT_EQ(hit.valid(), e.geometry != ~0u) << "ray " << i << " from " << ray.origin.transpose()
                                              << " along " << ray.direction.transpose();
    EXPECT_EQ(accel.occluded(ray), hit.valid()) << "ray " << i;
    if (!hit.valid()) {
      const Vec3 far = ray.origin + std::min(ray.tfar, 20.0) * ray.direction;
      missesOfTheBounds +=
          (ray.origin.cwiseAbs().maxCoeff() > 1.01 && far.cwiseAbs().maxCoeff() > 1.01);
      continue;
    }
    EXPECT_EQ(hit.geometry, e.geometry) << "ray " << i;
    EXPECT_NEAR(hit.t, e.t, e.geometry == 1u ? 1e-12 : 1e-6) << "ray " << i;
    hitsOnSphere += hit.geometry == 1u;
  }
  // Both kinds of ray were there in numbers.
  EXPECT_GT(hitsOnSphere, 1000);
  EXPECT_GT(missesOfTheBounds, 2000);
}

TEST(Accel, PacketsHitAsSingleRaysDo) {
  const FlushToZeroScope flushToZero;
  // Triangles (a wall and a chip on one side), quadric patches (a sphere) and Bézier pieces
  // (quadric-g1 on an icosphere on the other side), ids 0 to 3.
  const std::vector<QuadricPatch> patches = spherePatches();
  TriangleMesh wall, chip;
  wall.positions = {Vec3(-4, -3, 1.5), Vec3(4, -3, 1.5), Vec3(4, 3, 1.5), Vec3(-4, 3, 1.5)};
  wall.triangles = {{0, 1, 2}, {0, 2, 3}};
  chip.positions = {Vec3(-2.8, -0.6, -0.25), Vec3(-1.6, -0.6, -0.25), Vec3(-2.2, 0.6, -0.25)};
  chip.triangles = {{0, 1, 2}};
  TriangleMesh moved = icosphere(1);
  for (Vec3& p : moved.positions) p += Vec3(2.2, 0.3, 0);
  const G1Model g1(std::make_shared<const TriangleMesh>(moved));
  Accel accel;
  accel.addTriangles(wall);
  accel.addQuadricPatches(patches);
  accel.addTriangles(chip);
  accel.addBezierTriangles(g1.bezierPieces());
  accel.commit();
  Pcg32 rng(31);
  int perGeometry[4] = {0, 0, 0, 0};
  for (int packet = 0; packet < 600; ++packet) {
    // Camera-like bundles from one origin, and incoherent rays; packets of every size up to
    // past two of Embree's (37 rays are traced as 16 + 16 + 5).
    const size_t count = packet % 40 == 39 ? 37 : 1 + size_t(packet) % Accel::kPacketSize;
    const bool coherent = packet % 2 == 0;
    const Vec3 eye(8 * rng.nextDouble() - 4, 6 * rng.nextDouble() - 3, -4 - 2 * rng.nextDouble());
    const Vec3 towards = (Vec3(6 * rng.nextDouble() - 3, 2 * rng.nextDouble() - 1, 0) - eye);
    std::vector<Ray> rays(count);
    for (Ray& ray : rays) {
      if (coherent) {
        ray.origin = eye;
        ray.direction = (towards.normalized() + 0.08 * uniformDirection(rng)).normalized();
      } else {
        for (int a = 0; a < 3; ++a) ray.origin[a] = 6 * rng.nextDouble() - 3;
        ray.direction = uniformDirection(rng);
      }
      if (rng.nextDouble() < 0.2) ray.tnear = 0.5 * rng.nextDouble();
      if (rng.nextDouble() < 0.2) ray.tfar = 4 * rng.nextDouble();
    }
    for (Accel::HitNormal normal : {Accel::HitNormal::Fill, Accel::HitNormal::Skip}) {
      std::vector<RayHit> hits(count);
      accel.intersect(rays, hits, normal);
      for (size_t i = 0; i < count; ++i) {
        const RayHit one = accel.intersect(rays[i], normal);
        ASSERT_EQ(hits[i].geometry, one.geometry) << "packet " << packet << ", ray " << i;
        if (!one.valid()) continue;
        EXPECT_EQ(hits[i].primitive, one.primitive) << "packet " << packet << ", ray " << i;
        EXPECT_EQ(hits[i].t, one.t) << "packet " << packet << ", ray " << i;
        EXPECT_EQ(hits[i].u, one.u) << "packet " << packet << ", ray " << i;
        EXPECT_EQ(hits[i].v, one.v) << "packet " << packet << ", ray " << i;
        EXPECT_EQ(hits[i].geometricNormal, one.geometricNormal) << "packet " << packet;
        EXPECT_EQ(hits[i].point, one.point) << "packet " << packet << ", ray " << i;
        if (normal == Accel::HitNormal::Fill) ++perGeometry[one.geometry];
      }
    }
  }
  // Every kind of geometry was hit, in numbers.
  for (int count : perGeometry) EXPECT_GT(count, 100);
  std::vector<RayHit> two(2);
  EXPECT_THROW(accel.intersect(std::vector<Ray>(3), two), Error);

  // Embree's robust (watertight) kernels, which the crack-rate analysis builds: the same hits.
  Accel robust(Accel::Options{true});
  robust.addTriangles(wall);
  robust.addQuadricPatches(patches);
  robust.addTriangles(chip);
  robust.commit();
  int robustHits = 0;
  for (int packet = 0; packet < 100; ++packet) {
    const Vec3 eye(8 * rng.nextDouble() - 4, 6 * rng.nextDouble() - 3, -5);
    std::vector<Ray> rays(Accel::kPacketSize);
    for (Ray& ray : rays) {
      ray.origin = eye;
      ray.direction = (-eye.normalized() + 0.1 * uniformDirection(rng)).normalized();
    }
    std::vector<RayHit> hits(rays.size());
    robust.intersect(rays, hits);
    for (size_t i = 0; i < rays.size(); ++i) {
      const RayHit one = robust.intersect(rays[i]);
      ASSERT_EQ(hits[i].geometry, one.geometry) << "packet " << packet << ", ray " << i;
      EXPECT_EQ(hits[i].primitive, one.primitive) << "packet " << packet << ", ray " << i;
      EXPECT_EQ(hits[i].t, one.t) << "packet " << packet << ", ray " << i;
      EXPECT_EQ(hits[i].point, one.point) << "packet " << packet << ", ray " << i;
      robustHits += one.valid();
    }
  }
  EXPECT_GT(robustHits, 1500);

  // Without native triangles the rays go one by one: the same hits.
  Accel patchesOnly;
  patchesOnly.addQuadricPatches(patches);
  patchesOnly.commit();
  std::vector<Ray> rays(40);
  for (Ray& ray : rays) {
    ray.origin = 3.0 * uniformDirection(rng);
    ray.direction = (0.5 * uniformDirection(rng) - ray.origin).normalized();
  }
  std::vector<RayHit> hits(rays.size());
  patchesOnly.intersect(rays, hits);
  int valid = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    // Against the nearest root over every patch, found without Embree.
    double nearest = kInfinity;
    size_t which = 0;
    for (size_t k = 0; k < patches.size(); ++k) {
      double t;
      if (intersectPrimitive(patches, k, rays[i].origin, rays[i].direction, rays[i].tnear, nearest,
                             t))
        nearest = t, which = k;
    }
    ASSERT_EQ(hits[i].valid(), nearest < kInfinity) << "ray " << i;
    if (!hits[i].valid()) continue;
    EXPECT_EQ(hits[i].primitive, which) << "ray " << i;
    EXPECT_EQ(hits[i].t, nearest) << "ray " << i;
    valid += 1;
  }
  EXPECT_GT(valid, 30);
}

// A ray leaving a convex closed surface from a hit point into the outer hemisphere of the
// normal never meets the surface again; `offset` pushes the origin off along the normal.
void expectNoReintersection(const Accel& accel, double offset, uint64_t seed) {
  Pcg32 rng(seed);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 d0 = uniformDirection(rng);
    const RayHit hit = accel.intersect({Vec3::Zero(), d0});
    ASSERT_TRUE(hit.valid());
    const Vec3 n = hit.geometricNormal;
    ASSERT_GT(n.dot(d0), 0.0);
    Vec3 d = uniformDirection(rng);
    if (d.dot(n) < 0) d = -d;
    const Ray leaving{hit.t * d0 + offset * n, d};
    EXPECT_FALSE(accel.intersect(leaving).valid()) << "ray " << i;
    EXPECT_FALSE(accel.occluded(leaving)) << "ray " << i;
  }
}

TEST(Accel, TriangleReintersect) {
  const FlushToZeroScope flushToZero;
  const TriangleMesh mesh = icosphere(2);
  Accel accel;
  accel.addTriangles(mesh);
  accel.commit();
  // Float geometry: the offset covers float rounding of the hit point.
  expectNoReintersection(accel, 1e-5, 13);
}

TEST(Accel, QuadricPatchReintersect) {
  const FlushToZeroScope flushToZero;
  const std::vector<QuadricPatch> patches = spherePatches();
  Accel accel;
  accel.addQuadricPatches(patches);
  accel.commit();
  // Patches intersect in double: an offset of 1e-9 suffices.
  expectNoReintersection(accel, 1e-9, 17);
}

TEST(Accel, G1PiecesReintersect) {
  const FlushToZeroScope flushToZero;
  // quadric-g1 on a level-2 icosphere with the sphere's normals: a closed convex surface of
  // 960 quartic pieces, traced in double.
  const G1Model model(std::make_shared<const TriangleMesh>(icosphere(2)));
  Accel accel;
  accel.addBezierTriangles(model.bezierPieces());
  accel.commit();
  expectNoReintersection(accel, 1e-9, 23);
}

TEST(Accel, AllHitsReportsEveryCrossing) {
  const FlushToZeroScope flushToZero;
  const TriangleMesh mesh = icosphere(2);
  const std::vector<QuadricPatch> patches = spherePatches();
  Accel accel(Accel::Options{true, true});
  accel.addTriangles(mesh);
  accel.addQuadricPatches(patches);
  accel.commit();
  Pcg32 rng(19);
  for (int i = 0; i < 500; ++i) {
    // A line through the centre crosses the icosphere and the unit sphere twice each.
    const Vec3 d = uniformDirection(rng);
    std::vector<RayHit> hits;
    accel.allHits({-3.0 * d, d}, hits);
    ASSERT_EQ(hits.size(), 4u) << "line " << i;
    std::sort(hits.begin(), hits.end(), [](const RayHit& a, const RayHit& b) { return a.t < b.t; });
    EXPECT_NEAR(hits[0].t, 2.0, 1e-9);
    EXPECT_NEAR(hits[3].t, 4.0, 1e-9);
    EXPECT_LT(hits[0].geometricNormal.dot(d), 0.0);
    EXPECT_GT(hits[3].geometricNormal.dot(d), 0.0);
    EXPECT_NEAR(hits[1].t, accel.intersect({-3.0 * d, d, hits[0].t}).t, 1e-6);
  }
}

TEST(Accel, MisuseIsAnError) {
  TriangleMesh mesh;
  mesh.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  mesh.triangles = {{0, 1, 3}};
  Accel accel;
  EXPECT_THROW(accel.addTriangles(mesh), Error);  // index out of range
  mesh.triangles = {{0, 1, 2}};
  // A coordinate finite as a double but not as the float Embree reads is refused, by name.
  mesh.positions[1].x() = 1e300;
  try {
    accel.addTriangles(mesh);
    ADD_FAILURE() << "a vertex at 1e300 was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("vertex 1"), std::string::npos) << e.what();
  }
  // So is one that is a float but beyond the ±1.8e18 Embree traces (it would drop the triangle
  // from its tree without a word).
  mesh.positions[1].x() = -2e18;
  try {
    accel.addTriangles(mesh);
    ADD_FAILURE() << "a vertex at -2e18 was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("vertex 1 has a coordinate of -2e+18"), std::string::npos)
        << e.what();
  }
  mesh.positions[1].x() = 1.0;
  accel.addTriangles(mesh);
  EXPECT_THROW(accel.intersect({Vec3(0.2, 0.2, -1), Vec3(0, 0, 1)}), Error);  // not committed
  std::vector<QuadricPatch> bad(1);
  for (Vec4& plane : bad[0].planes) plane.setZero();
  bad[0].bounds.extend(Vec3(0, 0, 0));
  bad[0].bounds.hi.x() = std::nan("");
  EXPECT_THROW(accel.addQuadricPatches(bad), Error);
  // Among many patches (scanned in parallel blocks) the error names the first bad one, bad
  // bounds or a bridge that joins nothing of its geometry.
  std::vector<QuadricPatch> many(30000);
  for (QuadricPatch& p : many) p.bounds.extend(Vec3(0, 0, 0)), p.bounds.extend(Vec3(1, 1, 1));
  many[25000].bounds = Bounds3();
  many[17000].joins = {5, 40000};
  many[21000].bounds.lo.y() = kInfinity;
  const auto message = [&] {
    try {
      accel.addQuadricPatches(many);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message().find("quadric patch 17000: a bridge must join two patches of the same "
                           "geometry, not 40000"),
            std::string::npos)
      << message();
  many[17000].joins = {-1, -1};
  EXPECT_NE(message().find("quadric patch 21000: its bounds are empty, not finite or beyond"),
            std::string::npos)
      << message();
  // Finite, but beyond what Embree traces: it would drop the patch from its tree unsaid.
  many[21000].bounds = many[0].bounds;
  many[23000].bounds.hi.z() = 2e18;
  EXPECT_NE(message().find("quadric patch 23000: its bounds are empty, not finite or beyond"),
            std::string::npos)
      << message();
  accel.commit();
  EXPECT_THROW(accel.addTriangles(mesh), Error);  // already committed
  std::vector<RayHit> hits;
  EXPECT_THROW(accel.allHits({Vec3(0.2, 0.2, -1), Vec3(0, 0, 1)}, hits), Error);
  const Bounds3 b = accel.bounds();
  EXPECT_EQ(b.lo, Vec3(0, 0, 0));
  EXPECT_EQ(b.hi, Vec3(1, 1, 0));
}

TEST(Accel, RaysEmbreeCannotTraceAreAnErrorNotAnAbort) {
  // Embree's Debian build asserts that a ray's origin and direction lie within ±1.844e18 and
  // that tnear and tfar are numbers: such a ray aborted the process (a camera placed at 1e19,
  // a Python caller's ray from 1e30). Every path that traces refuses it by name instead.
  TriangleMesh floor;
  floor.positions = {Vec3(-1, 0, -1), Vec3(1, 0, -1), Vec3(1, 0, 1), Vec3(-1, 0, 1)};
  floor.triangles = {{0, 2, 1}, {0, 3, 2}};
  const std::vector<QuadricPatch> patches = spherePatches();
  Accel accel;
  accel.addTriangles(floor);
  accel.addQuadricPatches(patches);
  accel.commit();
  const Ray fine{Vec3(0.1, 1e17, 0.2), Vec3(0, -1, 0)};
  EXPECT_TRUE(accel.intersect(fine).valid());
  std::vector<Ray> bad(5, fine);
  bad[0].origin.y() = 1e19;
  bad[1].direction.x() = -3e18;
  bad[2].origin.z() = std::nan("");
  bad[3].tnear = std::nan("");
  bad[4].tfar = std::nan("");
  for (size_t i = 0; i < bad.size(); ++i) {
    const auto expectRefused = [&](const auto& trace, const char* how) {
      try {
        trace();
        ADD_FAILURE() << how << " traced bad ray " << i;
      } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("the largest Embree traces"), std::string::npos)
            << how << ": " << e.what();
      }
    };
    expectRefused([&] { accel.intersect(bad[i]); }, "intersect");
    expectRefused([&] { accel.occluded(bad[i]); }, "occluded");
    // In the middle of a packet, among good rays.
    std::vector<Ray> packet(Accel::kPacketSize, fine);
    packet[7] = bad[i];
    std::vector<RayHit> hits(packet.size());
    expectRefused([&] { accel.intersect(packet, hits); }, "a packet");
  }
  // The accel still traces after refusing.
  std::vector<Ray> packet(Accel::kPacketSize, fine);
  std::vector<RayHit> hits(packet.size());
  accel.intersect(packet, hits);
  for (const RayHit& hit : hits) EXPECT_EQ(hit.t, accel.intersect(fine).t);
}

}  // namespace
}  // namespace quadtri
