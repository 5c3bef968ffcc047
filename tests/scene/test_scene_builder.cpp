// Scene files to render objects: shapes placed as Mitsuba places them, the model override, and
// errors that name the XML line.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "fixtures/twisted_band.h"
#include "quadtri/math/error.h"
#include "quadtri/mesh/mesh_io.h"
#include "quadtri/mesh/shapes.h"
#include "quadtri/scene/scene_builder.h"
#include "quadtri/scene/scene_loader.h"

namespace quadtri {
namespace {

const char* kSensor = R"(<sensor type="perspective"><float name="fov" value="30"/>
  <transform name="to_world"><lookat origin="0, 0, 6" target="0, 0, 0" up="0, 1, 0"/></transform>
  <film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="4"/></film>
  <sampler type="independent"><integer name="sample_count" value="3"/><integer name="seed" value="5"/></sampler>
</sensor>)";

BuiltScene build(const std::string& body, const std::filesystem::path& file = "test.xml",
                 const std::optional<std::string>& model = std::nullopt) {
  return buildScene(parseSceneDescription("<scene version=\"3.0.0\">" + body + "</scene>", file),
                    model);
}

std::string errorOf(const std::string& body) {
  try {
    build(body);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(SceneBuilder, PlacesBuiltInShapesLikeMitsuba) {
  // A rectangle scaled by 2 and moved to z = −1 faces the camera; a sphere of radius 0.5 at
  // x = 3 is hit at its pole.
  const BuiltScene b = build(std::string(kSensor) + R"(
    <shape type="rectangle"><transform name="to_world"><scale value="2"/><translate value="0, 0, -1"/></transform></shape>
    <shape type="sphere"><point name="center" value="3, 0, 0"/><float name="radius" value="0.5"/></shape>)");
  EXPECT_EQ(b.options.samplesPerPixel, 3);
  EXPECT_EQ(b.options.seed, 5u);
  Ray ray;
  ray.origin = Vec3(1.9, 1.9, 5);
  ray.direction = Vec3(0, 0, -1);
  auto si = b.scene->intersect(ray);
  ASSERT_TRUE(si);
  EXPECT_NEAR(si->p.z(), -1.0, 1e-12);
  EXPECT_NEAR((si->geometricNormal - Vec3(0, 0, 1)).norm(), 0.0, 1e-12);
  ray.origin = Vec3(3, 5, 0);
  ray.direction = Vec3(0, -1, 0);
  si = b.scene->intersect(ray);
  ASSERT_TRUE(si);
  EXPECT_NEAR((si->p - Vec3(3, 0.5, 0)).norm(), 0.0, 1e-12);
  EXPECT_EQ(b.scene->primitiveCount(), 3u);
}

// A mesh file's tessellated model is tessellated at the level `auto` picks unless the shape
// names one: the highest (8) for a coarse mesh, 1 for a dense one (an icosphere of 81,920
// triangles strays by 1e-4 of its diagonal at most), and the level given otherwise.
TEST(SceneBuilder, TessellatedModelsPickTheirLevelUnlessTheShapeNamesOne) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "quadtri_scene_builder_tessellation";
  std::filesystem::create_directories(dir);
  saveMesh(makeBuiltin("icosahedron").mesh, dir / "coarse.ply");
  saveMesh(parseBuiltinSpec("icosphere:6")->mesh, dir / "dense.ply");
  const auto primitives = [&](const std::string& file, const std::string& tessellation) {
    const std::string named =
        tessellation.empty() ? ""
                             : R"(<string name="tessellation" value=")" + tessellation + R"("/>)";
    return build(std::string(kSensor) + R"(<shape type="ply"><string name="filename" value=")" +
                     file + R"("/><string name="model" value="pn"/>)" + named + "</shape>",
                 dir / "s.xml")
        .scene->primitiveCount();
  };
  EXPECT_EQ(primitives("coarse.ply", ""), 20u * 64u);
  EXPECT_EQ(primitives("dense.ply", ""), 81920u);
  EXPECT_EQ(primitives("dense.ply", "auto"), 81920u);
  EXPECT_EQ(primitives("dense.ply", "2"), 4u * 81920u);
  EXPECT_EQ(primitives("coarse.ply", "auto:0.5"), 20u);
  std::filesystem::remove_all(dir);
}

// A mirroring to_world reverses the winding after the loader built the mesh's edge adjacency:
// the models must not use the adjacency of the triangles as they were. Every ray towards the
// centre of a mirrored icosphere meets its curved surface once, near the unit sphere, as it
// does without the mirror.
TEST(SceneBuilder, MirroredMeshesAreConvertedWithTheirOwnEdges) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "quadtri_scene_builder_mirror";
  std::filesystem::create_directories(dir);
  saveMesh(parseBuiltinSpec("icosphere:2")->mesh, dir / "ball.ply");
  for (const char* model : {"quadric-param", "pn", "phong", "quadric-implicit", "quadric-g1"})
    for (const char* scale : {"1, 1, 1", "-1, 1, 1"}) {
      SCOPED_TRACE(std::string(model) + " scale " + scale);
      const BuiltScene b = build(std::string(kSensor) +
                                     R"(<shape type="ply"><string name="filename" value="ball.ply"/>
            <string name="model" value=")" +
                                     model +
                                     R"("/><string name="tessellation" value="3"/>
            <transform name="to_world"><scale value=")" +
                                     scale + R"("/></transform></shape>)",
                                 dir / "s.xml");
      double worst = 0.0;
      for (int i = 0; i < 400; ++i) {
        // Directions spread over the sphere (a Fibonacci lattice).
        const double z = 1.0 - (i + 0.5) / 200.0, phi = i * 2.399963229728653;
        const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
        const Vec3 towards(r * std::cos(phi), r * std::sin(phi), z);
        Ray ray;
        ray.origin = 3.0 * towards;
        ray.direction = -towards;
        const auto si = b.scene->intersect(ray);
        ASSERT_TRUE(si) << "ray " << i;
        worst = std::max(worst, std::abs(si->p.norm() - 1.0));
      }
      EXPECT_LT(worst, 0.01);
    }
  std::filesystem::remove_all(dir);
}

TEST(SceneBuilder, ModelOverrideAppliesToMeshesOnly) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "quadtri_scene_builder";
  std::filesystem::create_directories(dir);
  saveMesh(makeBuiltin("icosahedron").mesh, dir / "ico.obj");
  const std::string body = std::string(kSensor) + R"(
    <shape type="obj"><string name="filename" value="ico.obj"/><string name="model" value="flat"/></shape>
    <shape type="rectangle"><transform name="to_world"><translate value="0, 0, -3"/></transform></shape>)";
  EXPECT_EQ(build(body, dir / "s.xml").scene->primitiveCount(), 22u);
  // quadric-implicit: 20 patches instead of 20 triangles; the rectangle stays two triangles.
  const BuiltScene implicit = build(body, dir / "s.xml", std::string("quadric-implicit"));
  EXPECT_EQ(implicit.scene->primitiveCount(), 22u);
  EXPECT_EQ(implicit.inputTriangles, 20u);
  Ray ray;
  ray.origin = Vec3(0, 0, 5);
  ray.direction = Vec3(0, 0, -1);
  const auto si = implicit.scene->intersect(ray);
  ASSERT_TRUE(si);
  EXPECT_EQ(si->geometry->normals, GeometryRecord::Normals::Gradient);
  std::filesystem::remove_all(dir);
}

TEST(SceneBuilder, WarnsOnceForEachMeshWhoseModelFallsBack) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "quadtri_scene_warn";
  std::filesystem::create_directories(dir);
  // Two triangles facing +z with equal normals, one corner lifted: no quadratic edge through
  // the lifted corner can be tangent at both ends, so quadric-param gives up both patches.
  TriangleMesh step;
  step.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0.3), Vec3(0, 1, 0)};
  step.triangles = {{0, 1, 2}, {0, 2, 3}};
  step.normals = {Vec3::UnitZ()};
  step.normalIndices = {{0, 0, 0}, {0, 0, 0}};
  saveMesh(step, dir / "step.obj");
  saveMesh(makeBuiltin("icosahedron").mesh, dir / "ico.obj");
  const std::string body = std::string(kSensor) + R"(
    <shape type="obj"><string name="filename" value="step.obj"/><string name="model" value="quadric-param"/></shape>
    <shape type="obj"><string name="filename" value="ico.obj"/><string name="model" value="quadric-param"/></shape>
    <shape type="rectangle"/>)";
  const BuiltScene b = build(body, dir / "s.xml");
  ASSERT_EQ(b.warnings.size(), 1u);
  const std::string& w = b.warnings[0];
  EXPECT_EQ(w.rfind((dir / "s.xml").string() + ":", 0), 0u) << w;
  EXPECT_NE(w.find((dir / "step.obj").string() + ": quadric-param folds at "), std::string::npos)
      << w;
  EXPECT_NE(w.find(" and falls back on 100% of patches (2 of 2)"), std::string::npos) << w;
  // Deferred (as `quadtri render` builds, so that the first pixel does not wait for them), the
  // checks of every model with patches (tessellated, implicit, Bézier) are left one per mesh
  // shape and give the same warnings when run.
  const auto deferredBuild = [&](const std::optional<std::string>& model) {
    return buildScene(
        parseSceneDescription("<scene version=\"3.0.0\">" + body + "</scene>", dir / "s.xml"),
        model, 0, true);
  };
  EXPECT_TRUE(b.modelChecks.empty());
  for (const std::optional<std::string>& model :
       {std::optional<std::string>(), std::optional<std::string>("quadric-implicit"),
        std::optional<std::string>("quadric-g1")}) {
    SCOPED_TRACE(model.value_or("the scene's quadric-param"));
    const BuiltScene now = build(body, dir / "s.xml", model);
    const BuiltScene later = deferredBuild(model);
    EXPECT_TRUE(later.warnings.empty());
    ASSERT_EQ(later.modelChecks.size(), 2u);
    std::vector<std::string> ran;
    for (const ModelCheck& check : later.modelChecks)
      if (std::optional<std::string> warning = check()) ran.push_back(*warning);
    EXPECT_EQ(ran, now.warnings);
    // The step folds or falls back under both patch models; quadric-g1 holds on it.
    EXPECT_EQ(ran.size(), model == "quadric-g1" ? 0u : 1u);
  }
  // shading keeps the triangles: no check, deferred or not.
  EXPECT_TRUE(deferredBuild(std::string("shading")).modelChecks.empty());
  // The implicit model falls back on the step as quadric-param does.
  EXPECT_EQ(build(body, dir / "s.xml", std::string("quadric-implicit")).warnings.size(), 1u);
  // shading keeps the triangles: nothing to warn about.
  EXPECT_TRUE(build(body, dir / "s.xml", std::string("shading")).warnings.empty());
  std::filesystem::remove_all(dir);
}

TEST(SceneBuilder, ShadingOffsetFromTheSceneFileLiftsRayOrigins) {
  // An icosahedron scaled by 2 with the sphere's normals: its hits lift outwards in world
  // space; the rectangle and the `shading` override do not lift.
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "quadtri_scene_builder_offset";
  std::filesystem::create_directories(dir);
  saveMesh(makeBuiltin("icosahedron").mesh, dir / "ico.obj");
  const std::string body = std::string(kSensor) + R"(
    <shape type="obj"><string name="filename" value="ico.obj"/>
      <string name="model" value="shading-offset"/>
      <transform name="to_world"><scale value="2"/></transform></shape>
    <shape type="rectangle"><transform name="to_world"><translate value="0, 0, -3"/></transform></shape>)";
  Ray ray;
  ray.origin = Vec3(0.1, 0.2, 5);
  ray.direction = Vec3(0, 0, -1);
  Ray toRectangle;
  toRectangle.origin = Vec3(0.5, 0.9, -2);
  toRectangle.direction = Vec3(0, 0, -1);
  for (const std::optional<std::string>& model :
       {std::optional<std::string>(), std::optional<std::string>("shading-offset"),
        std::optional<std::string>("shading")}) {
    const bool lifts = !model || *model == "shading-offset";
    const BuiltScene b = build(body, dir / "s.xml", model);
    const auto si = b.scene->intersect(ray);
    ASSERT_TRUE(si);
    EXPECT_EQ(si->geometry->normals, GeometryRecord::Normals::Interpolated);
    EXPECT_EQ(si->geometry->liftRayOrigins, lifts);
    EXPECT_EQ(si->lifted, lifts);
    if (lifts)
      EXPECT_GT(si->liftedP.norm(), si->p.norm() + 0.05);
    else
      EXPECT_EQ(si->liftedP, si->p);
    const auto wall = b.scene->intersect(toRectangle);
    ASSERT_TRUE(wall);
    EXPECT_FALSE(wall->lifted);
  }
  std::filesystem::remove_all(dir);
}

TEST(SceneBuilder, ErrorsNameTheXmlLine) {
  // An area light on a non-uniformly scaled sphere (line 2 of the body's scene).
  const std::string sphere =
      errorOf(std::string(kSensor) +
              "\n<shape type=\"sphere\"><transform name=\"to_world\"><scale value=\"1, 2, 1\"/>"
              "</transform><emitter type=\"area\"/></shape>");
  EXPECT_NE(sphere.find("test.xml:6"), std::string::npos) << sphere;
  EXPECT_NE(sphere.find("similarity"), std::string::npos) << sphere;
  // A missing mesh file.
  const std::string missing =
      errorOf(std::string(kSensor) +
              "\n<shape type=\"obj\"><string name=\"filename\" value=\"nope.obj\"/></shape>");
  EXPECT_NE(missing.find("test.xml:6"), std::string::npos) << missing;
}

TEST(SceneBuilder, ChargesTheLongPatchesTracedInPartsLast) {
  // A band of slivers under quadric-implicit is traced in parts (quadric_patch_parts.h), which
  // the model's per-triangle charge leaves out: they are charged once built, last. The least
  // --max-memory that builds the scene is found by bisection; a byte less is refused, naming
  // the parts.
  const auto dir = std::filesystem::temp_directory_path() / "quadtri_scene_builder_parts";
  std::filesystem::create_directories(dir);
  saveMesh(fixtures::twistedBand(24, 6, 3.0), dir / "band.ply");
  const std::string xml = "<scene version=\"3.0.0\">" + std::string(kSensor) + R"(
    <shape type="ply"><string name="filename" value="band.ply"/><string name="model" value="quadric-implicit"/></shape></scene>)";
  const auto buildWithin = [&](uint64_t bytes) {
    return buildScene(parseSceneDescription(xml, dir / "s.xml"), std::nullopt, bytes);
  };
  const BuiltScene unlimited = buildWithin(0);
  ASSERT_GT(unlimited.scene->patchPartBytes(), 0u);
  uint64_t refused = 1, built = uint64_t(1) << 32;
  while (built - refused > 1) {
    const uint64_t middle = refused + (built - refused) / 2;
    try {
      buildWithin(middle);
      built = middle;
    } catch (const Error&) {
      refused = middle;
    }
  }
  std::string message;
  try {
    buildWithin(refused);
  } catch (const Error& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("tracing its long patches in parts needs about "), std::string::npos)
      << message;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace quadtri
