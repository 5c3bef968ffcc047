// `shading-offset` in the renderer: which rays leave from the lifted point, and the shadow
// terminator they remove.
#include <gtest/gtest.h>

#include "quadtri/render/integrator/direct_integrator.h"
#include "quadtri/render/integrator/path_integrator.h"
#include "quadtri/surface/shading_offset.h"
#include "render_fixtures.h"

namespace quadtri::testing {
namespace {

// One triangle in z = 0 with corner normals tilted outwards, so its inside is lifted.
TriangleMesh tiltedTriangle() {
  TriangleMesh mesh;
  mesh.positions = {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(0, 1, 0)};
  mesh.triangles = {{0, 1, 2}};
  mesh.normals = {Vec3(-0.5, -0.5, 1).normalized(), Vec3(0.5, -0.5, 1).normalized(),
                  Vec3(0, 0.6, 1).normalized()};
  mesh.normalIndices = {{0, 1, 2}};
  return mesh;
}

TEST(ShadingOffsetRender, RaysTowardsTheShadingSideLeaveFromTheLiftedPoint) {
  const TriangleMesh mesh = tiltedTriangle();
  // Barycentrics of (0.2, -0.3): b1 − b0 = 0.2 and b2 = 0.35.
  const double b2 = 0.35, b1 = (1.0 - b2 + 0.2) / 2.0, b0 = 1.0 - b1 - b2;
  const Vec3 lifted = shadingOffsetPoint(mesh, 0, Vec3(b0, b1, b2));
  const Vec3 p(0.2, -0.3, 0);
  ASSERT_GT(lifted.z() - p.z(), 0.05) << "the fixture lifts its inside";
  for (const char* model : {"shading", "shading-offset"}) {
    const bool lifts = std::string(model) == "shading-offset";
    RenderScene scene;
    addMesh(scene, mesh, model, diffuse(0.5));
    scene.commit();
    Ray ray;
    ray.origin = Vec3(0.2, -0.3, 2);
    ray.direction = Vec3(0, 0, -1);
    const auto si = scene.intersect(ray);
    ASSERT_TRUE(si) << model;
    EXPECT_EQ(si->lifted, lifts) << model;
    EXPECT_LT((si->liftedP - (lifts ? lifted : p)).norm(), 1e-6) << model;
    const Vec3 base = lifts ? si->liftedP : si->p;
    // A reflected (BSDF) ray and a shadow ray towards a light above the shading side.
    const Vec3 up = Vec3(0.3, 0.1, 1).normalized();
    EXPECT_LT((scene.spawnRay(*si, up).origin - (base + si->offset * si->geometricNormal)).norm(),
              1e-15)
        << model;
    const Vec3 light(-2, 1, 3);
    const Ray shadow = scene.spawnRayTo(*si, light, Vec3::Zero());
    EXPECT_LT((shadow.origin - (base + si->offset * si->geometricNormal)).norm(), 1e-15) << model;
    EXPECT_NEAR((shadow.origin + shadow.tfar * shadow.direction - light).norm(), 0.0, 1e-5);
    // Into the surface (transmission): from the hit itself, pushed below the plane.
    const Vec3 down = Vec3(0.1, -0.2, -1).normalized();
    EXPECT_LT(
        (scene.spawnRay(*si, down).origin - (si->p - si->offset * si->geometricNormal)).norm(),
        1e-15)
        << model;
  }
}

// A unit icosphere of level 1 (80 triangles) with the sphere's normals, a point light far away
// along `toLight`, and hits from random rays aimed at it: the fraction of hits that face the
// light by their shading normal (n_s·l > 0) yet whose shadow ray the sphere itself blocks.
struct TerminatorCount {
  int facing = 0, blocked = 0, facingBelowPlane = 0;
  double fraction() const { return double(blocked) / facing; }
};

TerminatorCount countTerminatorShadows(const std::string& model, const Vec3& toLight, double scale,
                                       const Vec3& centre) {
  ShapeParams params;
  params.level = 1;
  TriangleMesh mesh = makeBuiltin("icosphere", params).mesh;
  for (Vec3& p : mesh.positions) p = centre + scale * p;
  RenderScene scene;
  addMesh(scene, mesh, model, diffuse(0.5));
  const Vec3 light = centre + 100.0 * scale * toLight;
  scene.addPointLight(light, Color::Ones());
  scene.commit();
  Pcg32 rng(21);
  TerminatorCount count;
  for (int i = 0; i < 40000; ++i) {
    const Vec3 dir = squareToUniformSphere(rng.next2D());
    Ray ray;
    ray.origin = centre - 5.0 * scale * dir + 0.9 * scale * squareToUniformSphere(rng.next2D());
    ray.direction = dir;
    const auto si = scene.intersect(ray);
    if (!si) continue;
    const Vec3 l = safeNormalized(light - si->p);
    if (si->shadingNormal.dot(l) <= 0.0) continue;
    ++count.facing;
    count.facingBelowPlane += si->geometricNormal.dot(l) < 0.0;
    count.blocked += scene.occluded(scene.spawnRayTo(*si, light, Vec3::Zero()));
  }
  return count;
}

TEST(ShadingOffsetRender, TerminatorShadowsVanishOnACoarseIcosphere) {
  for (const Vec3& toLight : {Vec3(1, 0, 0), Vec3(0.3, 0.8, -0.52).normalized()}) {
    for (double scale : {1e-3, 1.0, 1e3}) {
      const Vec3 centre = Vec3(2, -1, 0.5) * scale;
      const TerminatorCount shading = countTerminatorShadows("shading", toLight, scale, centre);
      const TerminatorCount offset =
          countTerminatorShadows("shading-offset", toLight, scale, centre);
      const std::string what =
          "light " + std::to_string(toLight.x()) + " scale " + std::to_string(scale);
      // The same hits and shading normals: only the shadow rays' origins differ.
      EXPECT_EQ(shading.facing, offset.facing) << what;
      EXPECT_GT(shading.facing, 15000) << what;
      // Measured: 9.9% and 6.4% of the facing hits are in shadow under `shading`, every one of
      // them a hit whose light lies below its facet; none under `shading-offset`.
      EXPECT_GT(shading.fraction(), 0.05) << what;
      EXPECT_EQ(shading.blocked, shading.facingBelowPlane) << what;
      EXPECT_LT(offset.fraction(), 1e-3) << what;
    }
  }
}

// An albedo-1 diffuse sphere in a constant environment of radiance 1 has radiance 1 wherever
// every direction of the shading hemisphere sees the sky. `shading` loses the directions that
// point below the facet into the sphere; `shading-offset` must recover them, whether the sky is
// found by light samples (shadow rays), by BSDF samples (continuation rays), or by both in the
// path tracer.
PixelEstimate furnaceMean(const std::string& model, const Integrator& integrator, int spp) {
  RenderScene scene;
  ShapeParams params;
  params.level = 1;
  addMesh(scene, makeBuiltin("icosphere", params).mesh, model, diffuse(1.0));
  scene.setEnvironment(Color::Ones());
  // The sphere fills the frame: it subtends 27° around the axis, the frame 15°.
  scene.setCamera(makeCamera(Vec3(0, 0, 2.2), Vec3::Zero(), 30.0, 8, 8));
  scene.commit();
  RenderOptions options;
  options.samplesPerPixel = spp;
  options.threads = 2;
  const RenderResult r = render(scene, integrator, options);
  EXPECT_EQ(r.stats.nonFiniteSamples, 0u);
  return imageMean(r.image);
}

// True when `e` is consistent with expectation 1 (Z-test at level 1e-4; exact when noiseless).
bool consistentWithOne(const PixelEstimate& e) {
  if (e.standardError == 0.0) return std::abs(e.mean - 1.0) < 1e-9;
  return twoSidedNormalPValue((e.mean - 1.0) / e.standardError) > 1e-4;
}

TEST(ShadingOffsetRender, FurnaceOfACoarseIcosphere) {
  // Measured at 2048 spp (8×8 pixels): light samples only, shading 0.9874 ± 0.0035 and offset
  // 0.9941 ± 0.0035; BSDF samples only, shading 0.99355 ± 0.00059 and offset exactly 1 (every
  // one of the 131,072 cosine-sampled rays reaches the sky); path tracer, shading
  // 0.99314 ± 0.00092 and offset 1.00036 ± 0.00068.
  DirectIntegrator::Params lightOnly, bsdfOnly;
  lightOnly.bsdfSamples = 0;
  bsdfOnly.emitterSamples = 0;
  const PathIntegrator path({});
  const DirectIntegrator byLight(lightOnly), byBsdf(bsdfOnly);
  const PixelEstimate light = furnaceMean("shading-offset", byLight, 2048);
  EXPECT_TRUE(consistentWithOne(light)) << light.mean << " ± " << light.standardError;
  for (const Integrator* integrator :
       {static_cast<const Integrator*>(&byBsdf), static_cast<const Integrator*>(&path)}) {
    const PixelEstimate shading = furnaceMean("shading", *integrator, 2048);
    const PixelEstimate offset = furnaceMean("shading-offset", *integrator, 2048);
    EXPECT_LT(shading.mean + 5.0 * shading.standardError, 1.0)
        << integrator->toString() << ": shading " << shading.mean << " ± " << shading.standardError;
    EXPECT_TRUE(consistentWithOne(offset))
        << integrator->toString() << ": offset " << offset.mean << " ± " << offset.standardError;
  }
}

}  // namespace
}  // namespace quadtri::testing
