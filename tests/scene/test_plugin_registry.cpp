// The plugin registries (scene/plugin.h): every registered name parses into a description of
// that type, prints back with it and builds; an unknown name lists the registered ones.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>

#include "quadtri/math/error.h"
#include "quadtri/render/bsdf/bsdf.h"
#include "quadtri/render/integrator/integrator.h"
#include "quadtri/scene/bsdf/blend_xml.h"
#include "quadtri/scene/bsdf/diffuse_xml.h"
#include "quadtri/scene/plugin.h"
#include "quadtri/scene/scene_builder.h"
#include "quadtri/scene/scene_loader.h"

namespace quadtri {
namespace {

namespace fs = std::filesystem;

constexpr const char* kSensor =
    R"(<sensor type="perspective"><float name="fov" value="40"/>
         <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/>
         </film><sampler type="independent"><integer name="sample_count" value="16"/></sampler>
       </sensor>)";

SceneDescription parse(const std::string& body, const fs::path& file = "test.xml") {
  return parseSceneDescription("<scene version=\"3.0.0\">" + body + "</scene>", file);
}

std::string errorOf(const std::string& body) {
  try {
    parse(body);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

/// A folder with a one-triangle OBJ and PLY, removed at the end of the test.
class MeshFolder {
 public:
  MeshFolder() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() /
            (std::string("quadtri_registry_") + info->name() + "_" + std::to_string(getpid()));
    fs::create_directories(path_);
    std::ofstream(path_ / "tri.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    std::ofstream(path_ / "tri.ply")
        << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
           "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
           "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  }
  ~MeshFolder() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  fs::path scene() const { return path_ / "scene.xml"; }

 private:
  fs::path path_;
};

TEST(PluginRegistry, TablesHoldEveryPluginInOrder) {
  EXPECT_EQ(bsdfNames(), (std::vector<std::string>{"diffuse", "dielectric", "conductor",
                                                   "roughconductor", "twosided", "blendbsdf"}));
  EXPECT_EQ(emitterNames(), (std::vector<std::string>{"point", "constant", "area"}));
  EXPECT_EQ(shapeNames(), (std::vector<std::string>{"obj", "ply", "rectangle", "cube", "sphere"}));
  EXPECT_EQ(integratorNames(), (std::vector<std::string>{"path", "direct", "normals", "adaptive"}));
  for (const std::string& name : bsdfNames()) {
    ASSERT_TRUE(findBsdfPlugin(name)) << name;
    EXPECT_EQ(findBsdfPlugin(name)->name, name);
  }
  EXPECT_FALSE(findBsdfPlugin("velvet"));
  EXPECT_EQ(findEmitterPlugin("area")->place, EmitterPlace::Shape);
  EXPECT_EQ(findEmitterPlugin("point")->place, EmitterPlace::Scene);
  EXPECT_TRUE(findShapePlugin("ply"));
  EXPECT_TRUE(findIntegratorPlugin("adaptive"));
}

TEST(PluginRegistry, EveryBsdfNameRoundTripsAndBuilds) {
  // The least each type needs; a type registered without an entry here fails the test.
  const std::map<std::string, std::string> bodies = {
      {"diffuse", R"(<rgb name="reflectance" value="0.25"/>)"},
      {"dielectric", R"(<float name="int_ior" value="1.5"/>)"},
      {"conductor", R"(<string name="material" value="Au"/>)"},
      {"roughconductor", R"(<string name="distribution" value="ggx"/>)"},
      {"twosided", R"(<bsdf type="diffuse"/>)"},
      {"blendbsdf", R"(<float name="weight" value="0.25"/><bsdf type="diffuse"/>
                       <bsdf type="conductor"/>)"},
  };
  for (const std::string& name : bsdfNames()) {
    ASSERT_TRUE(bodies.count(name)) << "no test body for the registered BSDF " << name;
    const SceneDescription s = parse(std::string(kSensor) + "<bsdf type=\"" + name +
                                     "\" id=\"it\">" + bodies.at(name) + "</bsdf>");
    ASSERT_FALSE(s.bsdfs.empty()) << name;
    const BsdfDesc& desc = s.bsdfs.back();
    EXPECT_EQ(desc.type, name);
    EXPECT_EQ(desc.id, "it");
    EXPECT_EQ(desc.location, "test.xml:4");
    ASSERT_TRUE(desc.params) << name;
    const std::string text = toString(desc);
    EXPECT_EQ(text.rfind("<bsdf type=\"" + name + "\" id=\"it\"> (test.xml:4)", 0), 0u) << text;
    // The description builds the render object of its type.
    std::vector<std::shared_ptr<const Bsdf>> built;
    for (const BsdfDesc& d : s.bsdfs) built.push_back(d.params->build(built));
    ASSERT_TRUE(built.back()) << name;
    EXPECT_EQ(built.back()->toString().empty(), false) << name;
  }
}

TEST(PluginRegistry, EveryIntegratorNameRoundTripsAndBuilds) {
  for (const std::string& name : integratorNames()) {
    const SceneDescription s = parse(std::string(kSensor) + "<integrator type=\"" + name + "\"/>");
    EXPECT_EQ(s.integrator.type, name);
    ASSERT_TRUE(s.integrator.params) << name;
    EXPECT_EQ(toString(s.integrator).rfind("<integrator type=\"" + name + "\"> (test.xml:4)", 0),
              0u)
        << toString(s.integrator);
    const std::shared_ptr<const Integrator> integrator = s.integrator.params->build(16);
    ASSERT_TRUE(integrator) << name;
    // Only the adaptive integrator stops pixels early; its cap is the sampler's count.
    EXPECT_EQ(integrator->adaptive() != nullptr, name == "adaptive") << name;
    if (integrator->adaptive()) {
      EXPECT_EQ(integrator->adaptive()->maxSamples, 16);
    }
  }
}

TEST(PluginRegistry, EveryEmitterNameRoundTripsWhereItBelongs) {
  for (const EmitterPlugin& plugin : emitterPlugins()) {
    const std::string name(plugin.name);
    const std::string element = "<emitter type=\"" + name + "\"/>";
    if (plugin.place == EmitterPlace::Scene) {
      const SceneDescription s = parse(std::string(kSensor) + element);
      ASSERT_EQ(s.emitters.size(), 1u) << name;
      EXPECT_EQ(s.emitters[0].type, name);
      EXPECT_EQ(toString(s.emitters[0]).rfind("<emitter type=\"" + name + "\"> (test.xml:4)", 0),
                0u);
      EXPECT_NE(
          errorOf(std::string(kSensor) + "<shape type=\"cube\">" + element + "</shape>")
              .find("a <shape> may only contain an emitter of type 'area', got '" + name + "'"),
          std::string::npos);
    } else {
      const SceneDescription s =
          parse(std::string(kSensor) + "<shape type=\"cube\">" + element + "</shape>");
      ASSERT_EQ(s.shapes.size(), 1u) << name;
      ASSERT_TRUE(s.shapes[0].areaRadiance) << name;
      EXPECT_TRUE((*s.shapes[0].areaRadiance == 1.0).all());  // the default radiance
      EXPECT_NE(errorOf(std::string(kSensor) + element)
                    .find("test.xml:4: emitter '" + name + "' must be nested inside a <shape>"),
                std::string::npos);
    }
  }
}

TEST(PluginRegistry, EveryShapeNameRoundTripsAndBuilds) {
  const MeshFolder folder;
  const std::map<std::string, std::string> bodies = {
      {"obj", R"(<string name="filename" value="tri.obj"/>)"},
      {"ply", R"(<string name="filename" value="tri.ply"/>)"},
      {"rectangle", ""},
      {"cube", ""},
      {"sphere", R"(<float name="radius" value="0.5"/>)"},
  };
  std::string body = kSensor;
  for (const std::string& name : shapeNames()) {
    ASSERT_TRUE(bodies.count(name)) << "no test body for the registered shape " << name;
    body += "\n<shape type=\"" + name + "\">" + bodies.at(name) + "</shape>";
  }
  const fs::path file = folder.scene();
  std::ofstream(file) << "<scene version=\"3.0.0\">" << body << "</scene>";
  const SceneDescription s = loadSceneDescription(file);
  ASSERT_EQ(s.shapes.size(), shapeNames().size());
  for (size_t i = 0; i < s.shapes.size(); ++i) {
    EXPECT_EQ(s.shapes[i].type, shapeNames()[i]);
    EXPECT_EQ(s.shapes[i].location, file.string() + ":" + std::to_string(i + 5));
    EXPECT_EQ(toString(s.shapes[i]).rfind("<shape type=\"" + shapeNames()[i] + "\">", 0), 0u);
  }
  // The mesh files name their file in the description and count in the render key.
  EXPECT_EQ(s.shapes[0].params->files().size(), 1u);
  EXPECT_TRUE(s.shapes[2].params->files().empty());
  // One triangle from each file, two for the rectangle, twelve for the cube, one sphere.
  const BuiltScene built = buildScene(s);
  EXPECT_EQ(built.inputTriangles, 2u);
  EXPECT_EQ(built.scene->primitiveCount(), 1u + 1u + 2u + 12u + 1u);
}

TEST(PluginRegistry, UnknownTypesListTheRegisteredNames) {
  const std::string sensor = kSensor;
  const struct {
    std::string body, kind;
    std::vector<std::string> names;
  } cases[] = {
      {"<bsdf type=\"velvet\"/>", "bsdf", bsdfNames()},
      // Emitters say where the shape-level ones go.
      {"<emitter type=\"spot\"/>", "emitter", {"point", "constant", "area (inside a <shape>)"}},
      {"<shape type=\"torus\"/>", "shape", shapeNames()},
      {"<integrator type=\"bdpt\"/>", "integrator", integratorNames()},
  };
  for (const auto& c : cases) {
    const std::string message = errorOf(sensor + c.body);
    const std::string type = c.body.substr(
        c.body.find('"') + 1, c.body.find('"', c.body.find('"') + 1) - c.body.find('"') - 1);
    EXPECT_EQ(message, "test.xml:4: unknown " + c.kind + " type '" + type + "'; expected one of " +
                           joined(c.names))
        << message;
  }
}

TEST(PluginRegistry, BlendTakesItsTwoBsdfsInDocumentOrder) {
  // The plugin added through the registry alone (src/scene/bsdf/blend_xml.*, one table line).
  const SceneDescription s = parse(std::string(kSensor) + R"(<bsdf type="diffuse" id="d"/>
    <bsdf type="blendbsdf" id="mix"><float name="weight" value="0.3"/>
      <bsdf type="conductor"/><ref id="d"/></bsdf>)");
  ASSERT_EQ(s.bsdfs.size(), 3u);
  const BlendBsdfParams* blend = s.bsdfs[2].as<BlendBsdfParams>();
  ASSERT_TRUE(blend);
  EXPECT_DOUBLE_EQ(blend->weight, 0.3);
  EXPECT_EQ(blend->blended[0], 1u);  // the nested conductor, stored before the blend
  EXPECT_EQ(blend->blended[1], 0u);  // the referenced diffuse
  EXPECT_EQ(s.bsdfs[1].type, "conductor");
  EXPECT_NE(toString(s.bsdfs[2]).find("weight=0.3 bsdfs=[1, 0]"), std::string::npos);

  const std::string one = errorOf(std::string(kSensor) +
                                  "\n<bsdf type=\"blendbsdf\"><float name=\"weight\" "
                                  "value=\"0.5\"/><bsdf type=\"diffuse\"/></bsdf>");
  EXPECT_EQ(one, "test.xml:5: bsdf 'blendbsdf' needs exactly two nested <bsdf> or <ref>, got 1");
  const std::string weight = errorOf(std::string(kSensor) +
                                     "\n<bsdf type=\"blendbsdf\">\n<float name=\"weight\" "
                                     "value=\"2\"/></bsdf>");
  EXPECT_EQ(weight, "test.xml:6: bsdf 'blendbsdf': weight must be in [0, 1], got 2");
  const std::string missing = errorOf(std::string(kSensor) + "\n<bsdf type=\"blendbsdf\"/>");
  EXPECT_EQ(missing, "test.xml:5: bsdf 'blendbsdf' needs <float name=\"weight\" .../>");
}

TEST(PluginRegistry, AShapeWithoutBsdfGetsTheDefaultDiffuse) {
  const SceneDescription s = parse(std::string(kSensor) + "<shape type=\"cube\"/>");
  ASSERT_EQ(s.bsdfs.size(), 1u);
  EXPECT_EQ(s.bsdfs[0].type, "diffuse");
  EXPECT_EQ(s.bsdfs[0].location, "(default bsdf)");
  ASSERT_TRUE(s.bsdfs[0].as<DiffuseBsdfParams>());
  EXPECT_TRUE((s.bsdfs[0].as<DiffuseBsdfParams>()->reflectance == 0.5).all());
}

}  // namespace
}  // namespace quadtri
