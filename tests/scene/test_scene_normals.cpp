// A scene's mesh normals: `normals` and `crease_angle` on obj/ply shapes, the overrides of
// `render --normals/--crease-angle`, and what a file without normals renders with.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "quadtri/math/error.h"
#include "quadtri/mesh/mesh_io.h"
#include "quadtri/mesh/shapes.h"
#include "quadtri/scene/scene_builder.h"
#include "quadtri/scene/scene_loader.h"
#include "quadtri/scene/shape/mesh_file_xml.h"

namespace quadtri {
namespace {

namespace fs = std::filesystem;

const char* kSensor = R"(<sensor type="perspective"><float name="fov" value="30"/>
  <transform name="to_world"><lookat origin="0, 0, 6" target="0, 0, 0" up="0, 1, 0"/></transform>
  <film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="4"/></film>
</sensor>)";

class SceneNormals : public ::testing::Test {
 protected:
  fs::path dir = fs::temp_directory_path() /
                 ("quadtri_scene_normals_" +
                  std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
                  "_" + std::to_string(getpid()));
  void SetUp() override {
    fs::create_directories(dir);
    // The cube without normals: a file its reader must give normals.
    TriangleMesh cube = makeBuiltin("cube").mesh;
    cube.normals.clear();
    cube.normalIndices.clear();
    saveMesh(cube, dir / "cube.obj");
  }
  void TearDown() override { fs::remove_all(dir); }

  SceneDescription parse(const std::string& shapeBody) const {
    return parseSceneDescription(std::string("<scene version=\"3.0.0\">") + kSensor +
                                     "<shape type=\"cube\"/>\n<shape type=\"obj\">"
                                     "<string name=\"filename\" value=\"cube.obj\"/>" +
                                     shapeBody + "</shape></scene>",
                                 dir / "scene.xml");
  }
  std::string errorOf(const std::string& shapeBody) const {
    try {
      parse(shapeBody);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  }
};

TEST_F(SceneNormals, PropertiesAndTheirDefaults) {
  const SceneDescription plain = parse("");
  EXPECT_EQ(plain.shapes[1].as<MeshFileShapeParams>()->normals.source, NormalSource::File);
  EXPECT_EQ(plain.shapes[1].as<MeshFileShapeParams>()->normals.creaseAngleDeg, 30.0);
  const SceneDescription angle =
      parse(R"(<string name="normals" value="angle"/><float name="crease_angle" value="45"/>)");
  EXPECT_EQ(angle.shapes[1].as<MeshFileShapeParams>()->normals.source, NormalSource::Angle);
  EXPECT_EQ(angle.shapes[1].as<MeshFileShapeParams>()->normals.creaseAngleDeg, 45.0);
  EXPECT_EQ(parse(R"(<string name="normals" value="average"/>)")
                .shapes[1]
                .as<MeshFileShapeParams>()
                ->normals.source,
            NormalSource::Average);
}

TEST_F(SceneNormals, ErrorsNameTheLineAndTheValue) {
  const std::string bad = errorOf("\n<string name=\"normals\" value=\"smooth\"/>");
  EXPECT_NE(bad.find("scene.xml:6:"), std::string::npos) << bad;
  EXPECT_NE(bad.find("'smooth'"), std::string::npos) << bad;
  const std::string average = errorOf(
      "<string name=\"normals\" value=\"average\"/>\n<float name=\"crease_angle\" value=\"20\"/>");
  EXPECT_NE(average.find("scene.xml:6:"), std::string::npos) << average;
  EXPECT_NE(average.find("crease_angle"), std::string::npos) << average;
  const std::string range = errorOf("\n<float name=\"crease_angle\" value=\"200\"/>");
  EXPECT_NE(range.find("scene.xml:6:"), std::string::npos) << range;
  EXPECT_NE(range.find("200"), std::string::npos) << range;
}

TEST_F(SceneNormals, OverrideReachesMeshesOnly) {
  SceneDescription s = parse("");
  overrideNormals(s, NormalSource::Average, std::nullopt);
  EXPECT_EQ(s.shapes[1].as<MeshFileShapeParams>()->normals.source, NormalSource::Average);
  EXPECT_EQ(s.shapes[1].as<MeshFileShapeParams>()->normals.creaseAngleDeg, 30.0);
  overrideNormals(s, std::nullopt, 180.0);
  EXPECT_EQ(s.shapes[1].as<MeshFileShapeParams>()->normals.source, NormalSource::Average);
  EXPECT_EQ(s.shapes[1].as<MeshFileShapeParams>()->normals.creaseAngleDeg, 180.0);
  // The built-in cube has no normals to override: its parameters stay the ones parsed.
  EXPECT_EQ(s.shapes[0].type, "cube");
  EXPECT_FALSE(s.shapes[0].as<MeshFileShapeParams>());
  EXPECT_THROW(overrideNormals(s, std::nullopt, -5.0), Error);
}

TEST_F(SceneNormals, FileWithoutNormalsRendersWithCreaseNormals) {
  // A ray hits the cube's +z face at (0.9, 0.9): the shading normal there is the face's own
  // with the default crease normals, and leans towards the corner's diagonal with eq. 2.8.
  auto shadingNormal = [&](const std::string& shapeBody) {
    SceneDescription s =
        parseSceneDescription(std::string("<scene version=\"3.0.0\">") + kSensor +
                                  "<shape type=\"obj\">"
                                  "<string name=\"filename\" value=\"cube.obj\"/>" +
                                  shapeBody + "</shape></scene>",
                              dir / "scene.xml");
    const BuiltScene b = buildScene(s);
    Ray ray;
    ray.origin = Vec3(0.9, 0.9, 5);
    ray.direction = Vec3(0, 0, -1);
    const auto si = b.scene->intersect(ray);
    EXPECT_TRUE(si);
    return si ? si->shadingNormal : Vec3(Vec3::Zero());
  };
  EXPECT_NEAR((shadingNormal("") - Vec3(0, 0, 1)).norm(), 0.0, 1e-6);
  const Vec3 average = shadingNormal(R"(<string name="normals" value="average"/>)");
  EXPECT_GT(angleDegrees(average, Vec3(0, 0, 1)), 20.0);
  const Vec3 never = shadingNormal(R"(<float name="crease_angle" value="180"/>)");
  EXPECT_GT(angleDegrees(never, Vec3(0, 0, 1)), 20.0);
}

}  // namespace
}  // namespace quadtri
