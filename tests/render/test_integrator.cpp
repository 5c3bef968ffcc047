// The path tracer against scenes whose radiance is known in closed form.
#include <gtest/gtest.h>

#include "quadtri/render/bsdf/dielectric.h"
#include "quadtri/render/integrator/direct_integrator.h"
#include "quadtri/render/integrator/normals_integrator.h"
#include "quadtri/render/integrator/path_integrator.h"
#include "render_fixtures.h"

namespace quadtri::testing {
namespace {

// An albedo-1 diffuse object in a constant environment of radiance 1 reflects exactly what it
// receives: every pixel, on the object or not, has expectation 1.
void expectWhiteFurnace(RenderScene& scene) {
  scene.setEnvironment(Color::Ones());
  scene.setCamera(makeCamera(Vec3(0, 0, 3.2), Vec3::Zero(), 40.0, 8, 8));
  scene.commit();
  const PathIntegrator path({});
  expectPixelsMatch(scene, path, 1.0, 256);
  RenderOptions options;
  options.samplesPerPixel = 16;
  options.threads = 2;
  const RenderResult r = render(scene, path, options);
  const PixelEstimate m = imageMean(r.image);
  EXPECT_GT(twoSidedNormalPValue((m.mean - 1.0) / m.standardError), 1e-4)
      << m.mean << " ± " << m.standardError;
  EXPECT_EQ(r.stats.nonFiniteSamples, 0u);
}

TEST(PathIntegrator, WhiteFurnaceAnalyticSphere) {
  RenderScene scene;
  scene.addSphere(Vec3::Zero(), 1.0, Mat4::Identity(), false, diffuse(1.0), std::nullopt, "sphere");
  expectWhiteFurnace(scene);
}

TEST(PathIntegrator, WhiteFurnaceScaledEllipsoid) {
  // A non-uniform to_world turns the sphere into an ellipsoid quadric; far from the origin it
  // also exercises the ray offsets at larger coordinates.
  Mat4 toWorld = Mat4::Identity();
  toWorld.diagonal().head<3>() = Vec3(1.2, 0.6, 0.9);
  RenderScene scene;
  scene.addSphere(Vec3::Zero(), 1.0, toWorld, false, diffuse(1.0), std::nullopt, "ellipsoid");
  expectWhiteFurnace(scene);
}

// A smooth glass sphere neither absorbs nor emits: in the furnace every path ends in the
// environment carrying radiance 1, whatever it refracted or reflected on the way.
TEST(PathIntegrator, GlassSphereInFurnaceConservesEnergy) {
  RenderScene scene;
  scene.addSphere(Vec3::Zero(), 1.0, Mat4::Identity(), false,
                  std::make_shared<Dielectric>(1.5, 1.0), std::nullopt, "glass");
  expectWhiteFurnace(scene);
}

void icosphereFurnace(const std::string& model, int level) {
  RenderScene scene;
  ShapeParams params;
  params.level = level;
  addMesh(scene, makeBuiltin("icosphere", params).mesh, model, diffuse(1.0));
  expectWhiteFurnace(scene);
}

TEST(PathIntegrator, WhiteFurnaceFlatIcosphere) {
  icosphereFurnace("flat", 2);
}

// A tessellated model renders its tessellation as triangles with interpolated normals.
TEST(PathIntegrator, WhiteFurnaceTessellatedPhongIcosphere) {
  icosphereFurnace("phong", 1);
}

TEST(PathIntegrator, WhiteFurnaceTessellatedQuadricParamIcosphere) {
  icosphereFurnace("quadric-param", 1);
}

// Implicit quadric patches through Embree user geometry: the robust model turns an icosphere
// into patches of its exact circumscribed sphere, which close up.
TEST(PathIntegrator, WhiteFurnaceImplicitPatchesOfRobustModel) {
  icosphereFurnace("quadric-implicit-robust", 1);
}

// Bézier pieces traced directly through Embree user geometry: quadric-g1's surface of an
// icosphere is closed (C0), so the furnace holds.
TEST(PathIntegrator, WhiteFurnaceBezierPiecesOfG1Model) {
  icosphereFurnace("quadric-g1", 1);
}

// The thesis' implicit model as printed is not closed (its fourth clipping plane cuts into the
// patch; `crack_rate` 0.16 on icosphere:1), so light leaks through: the furnace must show a
// deficit well beyond noise. If the model ever closes up this test says so.
TEST(PathIntegrator, WhiteFurnaceShowsTheThesisImplicitModelsCracks) {
  RenderScene scene;
  ShapeParams params;
  params.level = 1;
  addMesh(scene, makeBuiltin("icosphere", params).mesh, "quadric-implicit", diffuse(1.0));
  scene.setEnvironment(Color::Ones());
  scene.setCamera(makeCamera(Vec3(0, 0, 3.2), Vec3::Zero(), 40.0, 8, 8));
  scene.commit();
  RenderOptions options;
  options.samplesPerPixel = 256;
  options.threads = 2;
  const PixelEstimate m = imageMean(render(scene, PathIntegrator({}), options).image);
  EXPECT_LT(m.mean + 5.0 * m.standardError, 1.0) << m.mean << " ± " << m.standardError;
}

// Point light of intensity I at the centre of a closed sphere of radius R and albedo ρ with
// inward normals: the first bounce leaves ρI/(πR²) and every further bounce multiplies the
// uniform radiance by ρ, so with max_depth D the camera sees ρI/(πR²)·Σ_{k<D−1} ρ^k.
double pointInSphereRadiance(double albedo, double intensity, double radius, int maxDepth) {
  const double first = albedo * intensity / (kPi * radius * radius);
  if (maxDepth < 0) return first / (1.0 - albedo);
  return first * (1.0 - std::pow(albedo, maxDepth - 1)) / (1.0 - albedo);
}

void pointInSphereScene(RenderScene& scene, double albedo, double intensity, double radius) {
  scene.addSphere(Vec3(0.3, -0.2, 0.1), radius, Mat4::Identity(), true, diffuse(albedo),
                  std::nullopt, "sphere");
  scene.addPointLight(Vec3(0.3, -0.2, 0.1), Color::Constant(intensity));
  scene.setCamera(makeCamera(Vec3(0.3, 0.2, 0.5), Vec3(0.3, -0.2, -1), 70.0, 6, 6));
  scene.commit();
}

TEST(PathIntegrator, PointLightInClosedSphereTruncatedSeries) {
  RenderScene scene;
  pointInSphereScene(scene, 0.6, 5.0, 2.0);
  for (int depth : {2, 3, 5}) {
    SCOPED_TRACE(depth);
    const PathIntegrator path({depth, 100, false});
    expectPixelsMatch(scene, path, pointInSphereRadiance(0.6, 5.0, 2.0, depth), 200);
  }
}

TEST(PathIntegrator, PointLightInClosedSphereUnboundedDepthWithRoulette) {
  RenderScene scene;
  pointInSphereScene(scene, 0.5, 3.0, 1.5);
  const PathIntegrator path({-1, 3, false});
  expectPixelsMatch(scene, path, pointInSphereRadiance(0.5, 3.0, 1.5, -1), 400);
}

// Inside a closed box whose walls emit Le and reflect with albedo ρ, the radiance is uniform
// and L = Le + ρL: L = Le/(1−ρ). Every wall is both the light (sampled by area) and what the
// BSDF samples hit, so the two MIS strategies must agree on their pdfs.
TEST(PathIntegrator, EmittingDiffuseBoxBalancesByMis) {
  RenderScene scene;
  addMesh(scene, inwardBox(Vec3(-1, -0.7, -1.3), Vec3(1.1, 0.8, 0.9)), "flat", diffuse(0.4),
          Color::Constant(2.0));
  scene.setCamera(makeCamera(Vec3(0.1, 0, 0), Vec3(0.2, 0.1, -1), 80.0, 6, 6));
  scene.commit();
  expectPixelsMatch(scene, PathIntegrator({-1, 4, false}), 2.0 / 0.6, 300);
  // With the emitters hidden from the camera, what is left is the reflected part ρL.
  expectPixelsMatch(scene, PathIntegrator({-1, 4, true}), 0.4 * 2.0 / 0.6, 300);
  // Direct lighting stops after one reflection: Le(1 + ρ), with any mix of sample counts.
  // (Light sampling alone is left out here: near the box's edges its estimator is unbiased but
  // heavy-tailed, so a Z-test of a few hundred samples would reject it; see SphereAreaLight.)
  for (const DirectIntegrator::Params& p :
       {DirectIntegrator::Params{1, 1, false}, {2, 1, false}, {0, 2, false}}) {
    SCOPED_TRACE(DirectIntegrator(p).toString());
    expectPixelsMatch(scene, DirectIntegrator(p), 2.0 * 1.4, 200);
  }
  expectPixelsMatch(scene, PathIntegrator({2, 4, false}), 2.0 * 1.4, 300);
}

// A diffuse floor under a sphere of radiance Le (a black diffuse sphere, so nothing bounces
// back): straight below the centre at distance d the floor receives E = πLe(r/d)² and shows
// ρLe(r/d)². A 0.2° field of view keeps the pixel on that point.
TEST(PathIntegrator, SphereAreaLightOverFloor) {
  RenderScene scene;
  TriangleMesh floor;
  floor.positions = {Vec3(-50, 0, -50), Vec3(50, 0, -50), Vec3(50, 0, 50), Vec3(-50, 0, 50)};
  floor.triangles = {{0, 2, 1}, {0, 3, 2}};
  addMesh(scene, floor, "flat", diffuse(0.7));
  scene.addSphere(Vec3(0, 2, 0), 0.5, Mat4::Identity(), false, diffuse(0.0), Color::Constant(4.0),
                  "light");
  scene.setCamera(makeCamera(Vec3(3, 1, 0), Vec3::Zero(), 0.2, 2, 2));
  scene.commit();
  const double expected = 0.7 * 4.0 * 0.25 / 4.0;
  expectPixelsMatch(scene, PathIntegrator({2, 100, false}), expected, 2000);
  expectPixelsMatch(scene, PathIntegrator({-1, 5, false}), expected, 2000);
  expectPixelsMatch(scene, DirectIntegrator({2, 1, false}), expected, 1000);
  expectPixelsMatch(scene, DirectIntegrator({2, 0, false}), expected, 1000);
  expectPixelsMatch(scene, DirectIntegrator({0, 2, false}), expected, 4000);
}

TEST(PathIntegrator, RejectsInvalidDepths) {
  EXPECT_THROW(PathIntegrator({0, 5, false}), Error);
  EXPECT_THROW(PathIntegrator({-2, 5, false}), Error);
  EXPECT_THROW(PathIntegrator({-1, 0, false}), Error);
  EXPECT_THROW(DirectIntegrator({0, 0, false}), Error);
}

TEST(NormalsIntegrator, ColoursTheSphereNormal) {
  RenderScene scene;
  scene.addSphere(Vec3::Zero(), 1.0, Mat4::Identity(), false, diffuse(0.5), std::nullopt, "sphere");
  scene.setCamera(makeCamera(Vec3(0, 0, 5), Vec3::Zero(), 30.0, 9, 9));
  scene.commit();
  const NormalsIntegrator normals;
  uint64_t rays = 0;
  Pcg32 rng;
  // The centre pixel's centre ray hits the sphere at (0, 0, 1): colour (0.5, 0.5, 1).
  const Color c = normals.radiance(scene, scene.camera().generateRay(Vec2(4.5, 4.5)), rng, rays);
  EXPECT_NEAR(c[0], 0.5, 1e-6);
  EXPECT_NEAR(c[1], 0.5, 1e-6);
  EXPECT_NEAR(c[2], 1.0, 1e-6);
  // A corner ray misses: black.
  EXPECT_TRUE(isBlack(normals.radiance(scene, scene.camera().generateRay(Vec2(0, 0)), rng, rays)));
  EXPECT_EQ(rays, 2u);
}

}  // namespace
}  // namespace quadtri::testing
