// Hits and ray spawning: shading data at hits, and rays that leave a surface without finding it
// again (pbrt's Reintersect tests) or leaking through their target.
#include <gtest/gtest.h>

#include "render_fixtures.h"

namespace quadtri::testing {
namespace {

// Rays from far away at a closed convex object: a ray spawned from the hit towards the outside
// must hit nothing, and one towards the inside must cross to the far side, well away from the
// start. Repeated at scales 1e-3 … 1e4 with the object a few times its size from the origin,
// and at scale 1 a million times its size away. The spawn offset stays within `maxOffset` times
// the scale.
void expectNoSelfIntersection(const std::function<void(RenderScene&, double, const Vec3&)>& build,
                              double maxOffset) {
  const std::pair<double, Vec3> placements[] = {{1e-3, Vec3(3.0, -2.0, 1.5) * 1e-3},
                                                {1.0, Vec3(3.0, -2.0, 1.5)},
                                                {1e4, Vec3(3.0, -2.0, 1.5) * 1e4},
                                                {1.0, Vec3(1e6, -1e6, 5e5)}};
  for (const auto& [scale, centre] : placements) {
    RenderScene scene;
    build(scene, scale, centre);
    scene.commit();
    Pcg32 rng(uint64_t(scale * 1000) + uint64_t(centre.norm()));
    int hits = 0;
    for (int i = 0; i < 4000; ++i) {
      const Vec3 dir = squareToUniformSphere(rng.next2D());
      Ray ray;
      ray.origin = centre - 10.0 * scale * dir + 0.5 * scale * squareToUniformSphere(rng.next2D());
      ray.direction = dir;
      const auto si = scene.intersect(ray);
      if (!si) continue;
      ++hits;
      ASSERT_LE(si->offset, maxOffset * scale) << "scale " << scale << " ray " << i;
      const Vec3 n = si->geometricNormal;
      Vec3 out = squareToCosineHemisphere(rng.next2D());
      Vec3 s, t;
      orthonormalBasis(n, s, t);
      out = safeNormalized(out.x() * s + out.y() * t + out.z() * n);
      ASSERT_FALSE(scene.intersect(scene.spawnRay(*si, out))) << "scale " << scale << " ray " << i;
      const auto far = scene.intersect(scene.spawnRay(*si, -out));
      ASSERT_TRUE(far) << "scale " << scale << " ray " << i;
      EXPECT_GT(far->t, 1e-4 * scale) << "scale " << scale << " ray " << i;
    }
    EXPECT_GT(hits, 400);
  }
}

TEST(RenderScene, SpawnedRaysLeaveAnalyticSpheres) {
  expectNoSelfIntersection(
      [](RenderScene& scene, double scale, const Vec3& centre) {
        scene.addSphere(centre, scale, Mat4::Identity(), false, diffuse(0.5), std::nullopt,
                        "sphere");
      },
      0.05);  // far from the origin the sphere's quadric rounds to about 1e-3 of its radius
}

TEST(RenderScene, SpawnedRaysLeaveTriangles) {
  expectNoSelfIntersection(
      [](RenderScene& scene, double scale, const Vec3& centre) {
        ShapeParams params;
        params.level = 3;
        TriangleMesh mesh = makeBuiltin("icosphere", params).mesh;
        for (Vec3& p : mesh.positions) p = centre + scale * p;
        addMesh(scene, mesh, "flat", diffuse(0.5));
      },
      1e-4);
}

// Inside a box every wall sees every other: a shadow ray between two wall points is never
// blocked, even when it grazes the target's wall near a shared edge.
// Also a million times its size from the origin, where the room is traced relative to its centre.
TEST(RenderScene, ShadowRaysInsideAConvexRoomAreNeverBlocked) {
  for (const Vec3& shift : {Vec3::Zero().eval(), Vec3(1e6, 1e6, -1e6)}) {
    RenderScene scene;
    auto box = std::make_shared<TriangleMesh>(
        inwardBox(shift + Vec3(-1, -0.7, -1.3), shift + Vec3(1.1, 0.8, 0.9)));
    addMesh(scene, *box, "flat", diffuse(0.5), Color::Ones());
    scene.commit();
    Pcg32 rng(3);
    int tested = 0;
    for (int i = 0; i < 20000; ++i) {
      Ray ray;
      ray.origin = shift + Vec3(0.05, 0.05, -0.2);
      ray.direction = squareToUniformSphere(rng.next2D());
      const auto si = scene.intersect(ray);
      ASSERT_TRUE(si);
      const LightSampler::Choice choice = scene.lightSampler().choose(rng.nextDouble());
      const auto ls = choice.light->sampleLi(si->p, rng.next2D());
      if (!ls || ls->direction.dot(si->geometricNormal) <= 0.0) continue;
      ++tested;
      ASSERT_FALSE(scene.occluded(scene.spawnRayTo(*si, ls->point, ls->normal)))
          << "sample " << i << " shifted by " << shift.transpose();
    }
    EXPECT_GT(tested, 10000);
  }
}

// A sphere light's samples lie on the exact sphere, the sphere the scene traces is a quadric in
// world coordinates: a million units from the origin its terms cancel to about 1e-4, and a
// shadow ray that stopped at float error short of the sample met the light itself (half of them
// for radius 1). LightSample::pointError keeps them short of the traced surface.
TEST(RenderScene, ShadowRaysReachASphereLightFarFromTheOrigin) {
  for (const Vec3& shift : {Vec3::Zero().eval(), Vec3(1e6, -1e6, 5e5)})
    for (const double radius : {1.0, 0.1}) {
      RenderScene scene;
      TriangleMesh floor;
      floor.positions = {shift + Vec3(-5, -5, 0), shift + Vec3(5, -5, 0), shift + Vec3(5, 5, 0),
                         shift + Vec3(-5, 5, 0)};
      floor.triangles = {{0u, 1u, 2u}, {0u, 2u, 3u}};
      addMesh(scene, floor, "flat", diffuse(0.5));
      scene.addSphere(shift + Vec3(0, 0, 3), radius, Mat4::Identity(), false, diffuse(0.0),
                      Color::Ones(), "light");
      scene.commit();
      Pcg32 rng(7);
      int tested = 0;
      for (int i = 0; i < 5000; ++i) {
        const Vec2 xy = rng.next2D();
        const auto si =
            scene.intersect({shift + Vec3(4 * xy.x() - 2, 4 * xy.y() - 2, 1), Vec3(0, 0, -1)});
        ASSERT_TRUE(si);
        const auto ls =
            scene.lightSampler().choose(rng.nextDouble()).light->sampleLi(si->p, rng.next2D());
        if (!ls) continue;
        ++tested;
        ASSERT_FALSE(scene.occluded(scene.spawnRayTo(*si, ls->point, ls->normal, ls->pointError)))
            << "sample " << i << ", radius " << radius << ", shifted by " << shift.transpose();
      }
      EXPECT_GT(tested, 4000);
    }
}

TEST(RenderScene, ShadingNormalsFollowTheModel) {
  // One triangle with tilted corner normals: `shading` interpolates them barycentrically,
  // `flat` uses the face normal.
  TriangleMesh mesh;
  mesh.positions = {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(0, 1, 0)};
  mesh.triangles = {{0, 1, 2}};
  mesh.normals = {Vec3(-0.3, 0, 1).normalized(), Vec3(0.3, 0, 1).normalized(),
                  Vec3(0, 0.5, 1).normalized()};
  mesh.normalIndices = {{0, 1, 2}};
  for (const char* model : {"flat", "shading"}) {
    RenderScene scene;
    addMesh(scene, mesh, model, diffuse(0.5));
    scene.commit();
    Ray ray;
    ray.origin = Vec3(0.2, -0.3, 2);
    ray.direction = Vec3(0, 0, -1);
    const auto si = scene.intersect(ray);
    ASSERT_TRUE(si) << model;
    EXPECT_NEAR((si->p - Vec3(0.2, -0.3, 0)).norm(), 0.0, 1e-6);
    EXPECT_NEAR((si->geometricNormal - Vec3(0, 0, 1)).norm(), 0.0, 1e-12);
    // Barycentrics of (0.2, -0.3): b1 − b0 = 0.2 and b2 = 0.35.
    const double b2 = 0.35, b1 = (1.0 - b2 + 0.2) / 2.0, b0 = 1.0 - b1 - b2;
    const Vec3 expected =
        std::string(model) == "flat"
            ? Vec3(0, 0, 1)
            : Vec3(b0 * mesh.normals[0] + b1 * mesh.normals[1] + b2 * mesh.normals[2]).normalized();
    EXPECT_NEAR((si->shadingNormal - expected).norm(), 0.0, 1e-6) << model;
  }
}

TEST(RenderScene, EllipsoidQuadricFromAScaledSphere) {
  // to_world = scale (2, 1, 0.5) then translate (1, 0, 0): hits along the axes land on the
  // ellipsoid's poles with the axis as normal.
  Mat4 m = Mat4::Identity();
  m.diagonal().head<3>() = Vec3(2, 1, 0.5);
  m(0, 3) = 1.0;
  RenderScene scene;
  scene.addSphere(Vec3::Zero(), 1.0, m, false, diffuse(0.5), std::nullopt, "ellipsoid");
  scene.commit();
  Ray ray;
  ray.origin = Vec3(10, 0, 0);
  ray.direction = Vec3(-1, 0, 0);
  auto si = scene.intersect(ray);
  ASSERT_TRUE(si);
  EXPECT_NEAR((si->p - Vec3(3, 0, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((si->shadingNormal - Vec3(1, 0, 0)).norm(), 0.0, 1e-12);
  ray.origin = Vec3(1, 0, -10);
  ray.direction = Vec3(0, 0, 1);
  si = scene.intersect(ray);
  ASSERT_TRUE(si);
  EXPECT_NEAR((si->p - Vec3(1, 0, -0.5)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((si->shadingNormal - Vec3(0, 0, -1)).norm(), 0.0, 1e-12);
  EXPECT_EQ(scene.primitiveCount(), 1u);
  // An emitting sphere must stay a sphere.
  RenderScene bad;
  EXPECT_THROW(bad.addSphere(Vec3::Zero(), 1.0, m, false, diffuse(0.5), Color::Ones(), "light"),
               Error);
}

}  // namespace
}  // namespace quadtri::testing
