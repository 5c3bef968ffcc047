#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "quadtri/math/error.h"
#include "quadtri/scene/bsdf/conductor_xml.h"
#include "quadtri/scene/bsdf/dielectric_xml.h"
#include "quadtri/scene/bsdf/diffuse_xml.h"
#include "quadtri/scene/bsdf/rough_conductor_xml.h"
#include "quadtri/scene/emitter/constant_xml.h"
#include "quadtri/scene/emitter/point_xml.h"
#include "quadtri/scene/integrator/adaptive_xml.h"
#include "quadtri/scene/integrator/direct_xml.h"
#include "quadtri/scene/integrator/normals_xml.h"
#include "quadtri/scene/integrator/path_xml.h"
#include "quadtri/scene/scene_loader.h"
#include "quadtri/scene/shape/mesh_file_xml.h"

namespace quadtri {
namespace {

namespace fs = std::filesystem;

/// A minimal valid sensor, for scenes whose test is about something else.
constexpr const char* kSensor =
    R"(<sensor type="perspective"><float name="fov" value="40"/></sensor>)";

/// `body` inside <scene version="3.0.0">, all on line 1 unless `body` has newlines.
SceneDescription parse(const std::string& body, const SceneDefines& defines = {}) {
  return parseSceneDescription("<scene version=\"3.0.0\">" + body + "</scene>", "test.xml",
                               defines);
}

/// The message of the Error that parsing `xml` throws ("" when it does not throw).
std::string errorOf(const std::string& xml, const fs::path& file = "test.xml",
                    const SceneDefines& defines = {}) {
  try {
    parseSceneDescription(xml, file, defines);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

/// A fresh folder for scene files that reference other files.
class TempFolder {
 public:
  TempFolder() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() /
            (std::string("quadtri_scene_") + info->name() + "_" + std::to_string(getpid()));
    fs::create_directories(path_);
  }
  ~TempFolder() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  fs::path write(const std::string& name, const std::string& text) const {
    const fs::path p = path_ / name;
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
    return p;
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

constexpr const char* kTriangleObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

Vec3 apply(const Mat4& m, const Vec3& p) {
  return (m * p.homogeneous()).head<3>();
}

Mat4 shapeTransform(const std::string& transformBody) {
  const SceneDescription s =
      parse(std::string(kSensor) + "<shape type=\"cube\"><transform name=\"to_world\">" +
            transformBody + "</transform></shape>");
  return s.shapes.at(0).toWorld;
}

TEST(Scene, DeepNestingIsAnErrorNotAStackOverflow) {
  // 100,000 nested elements: refused by an iterative walk before any recursive reader.
  std::string xml = "<scene version=\"3.0.0\">";
  const int depth = 100000;
  for (int i = 0; i < depth; ++i) xml += "<bsdf type=\"diffuse\">";
  for (int i = 0; i < depth; ++i) xml += "</bsdf>";
  xml += "</scene>";
  EXPECT_NE(errorOf(xml).find("test.xml:1: elements nest deeper than 64 levels"), std::string::npos)
      << errorOf(xml);
}

TEST(SceneSensor, LookAtMapsOriginAndViewDirection) {
  const SceneDescription s = parse(R"(
    <sensor type="perspective">
      <float name="fov" value="35"/> <string name="fov_axis" value="smaller"/>
      <float name="near_clip" value="0.1"/> <float name="far_clip" value="500"/>
      <transform name="to_world">
        <lookat origin="1, 2, 3" target="1, 2, -1" up="0, 1, 0"/>
      </transform>
      <film type="hdrfilm">
        <integer name="width" value="320"/> <integer name="height" value="200"/>
        <rfilter type="gaussian"><float name="stddev" value="0.3"/></rfilter>
      </film>
      <sampler type="independent">
        <integer name="sample_count" value="64"/> <integer name="seed" value="7"/>
      </sampler>
    </sensor>)");
  const SensorDesc& c = s.sensor;
  EXPECT_DOUBLE_EQ(c.fov, 35.0);
  EXPECT_EQ(c.fovAxis, FovAxis::Smaller);
  EXPECT_DOUBLE_EQ(c.nearClip, 0.1);
  EXPECT_DOUBLE_EQ(c.farClip, 500.0);
  EXPECT_EQ(c.film.width, 320);
  EXPECT_EQ(c.film.height, 200);
  EXPECT_EQ(c.film.filter.type, FilterDesc::Type::Gaussian);
  EXPECT_DOUBLE_EQ(c.film.filter.stddev, 0.3);
  EXPECT_EQ(c.sampler.sampleCount, 64);
  EXPECT_EQ(c.sampler.seed, 7);
  EXPECT_EQ(c.location, "test.xml:2");
  EXPECT_LT((apply(c.toWorld, Vec3::Zero()) - Vec3(1, 2, 3)).norm(), 1e-14);
  // Local +z is the unit direction towards the target, local +y the world up.
  EXPECT_LT((c.toWorld.block<3, 1>(0, 2) - Vec3(0, 0, -1)).norm(), 1e-14);
  EXPECT_LT((c.toWorld.block<3, 1>(0, 1) - Vec3(0, 1, 0)).norm(), 1e-14);
  // Mitsuba's x axis is up × forward: here (0,1,0) × (0,0,-1) = (-1,0,0).
  EXPECT_LT((c.toWorld.block<3, 1>(0, 0) - Vec3(-1, 0, 0)).norm(), 1e-14);
}

TEST(SceneSensor, ObliqueLookAtIsOrthonormalAndAimsAtTarget) {
  const SceneDescription s = parse(R"(<sensor type="perspective"><float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="3,4,5" target="0,1,-2" up="0,0.3,1"/></transform>
    </sensor>)");
  const Mat3 r = s.sensor.toWorld.block<3, 3>(0, 0);
  EXPECT_LT((r.transpose() * r - Mat3::Identity()).norm(), 1e-14);
  EXPECT_NEAR(r.determinant(), 1.0, 1e-14);
  const Vec3 toTarget = (Vec3(0, 1, -2) - Vec3(3, 4, 5)).normalized();
  EXPECT_LT((apply(s.sensor.toWorld, Vec3(0, 0, 2.5)) - (Vec3(3, 4, 5) + 2.5 * toTarget)).norm(),
            1e-13);
}

TEST(SceneSensor, DefaultsFollowMitsuba) {
  const SceneDescription s = parse(kSensor);
  EXPECT_EQ(s.sensor.fovAxis, FovAxis::X);
  EXPECT_DOUBLE_EQ(s.sensor.nearClip, 1e-2);
  EXPECT_DOUBLE_EQ(s.sensor.farClip, 1e4);
  EXPECT_EQ(s.sensor.film.width, 768);
  EXPECT_EQ(s.sensor.film.height, 576);
  EXPECT_EQ(s.sensor.film.filter.type, FilterDesc::Type::Gaussian);
  EXPECT_DOUBLE_EQ(s.sensor.film.filter.stddev, 0.5);
  EXPECT_EQ(s.sensor.sampler.sampleCount, 4);
  EXPECT_TRUE(s.sensor.toWorld.isIdentity());
  EXPECT_EQ(s.integrator.type, "path");
  ASSERT_TRUE(s.integrator.as<PathIntegratorParams>());
  EXPECT_EQ(s.integrator.as<PathIntegratorParams>()->path.maxDepth, -1);
}

TEST(SceneTransform, RotateTranslateScaleMatrix) {
  // 90 degrees about z maps x to y; the axis may be given as value or x/y/z.
  for (const char* rotate :
       {R"(<rotate z="1" angle="90"/>)", R"(<rotate value="0,0,2" angle="90"/>)",
        R"(<rotate axis="0 0 1" angle="90"/>)"}) {
    const Mat4 m = shapeTransform(rotate);
    EXPECT_LT((apply(m, Vec3(1, 0, 0)) - Vec3(0, 1, 0)).norm(), 1e-15) << rotate;
    EXPECT_LT((apply(m, Vec3(0, 0, 1)) - Vec3(0, 0, 1)).norm(), 1e-15) << rotate;
  }
  // <translate/> then <scale/>: the scale applies after the translation, M = S·T.
  const Mat4 ts = shapeTransform(R"(<translate x="1" y="2" z="3"/><scale value="2"/>)");
  EXPECT_LT((apply(ts, Vec3(1, 1, 1)) - Vec3(4, 6, 8)).norm(), 1e-15);
  const Mat4 st = shapeTransform(R"(<scale x="2" y="3"/><translate value="1, 2, 3"/>)");
  EXPECT_LT((apply(st, Vec3(1, 1, 1)) - Vec3(3, 5, 4)).norm(), 1e-15);
  // <matrix> is row-major: the last column holds the translation.
  const Mat4 m = shapeTransform(R"(<matrix value="0 -1 0 5  1 0 0 6  0 0 1 7  0 0 0 1"/>)");
  EXPECT_LT((apply(m, Vec3(1, 0, 0)) - Vec3(5, 7, 7)).norm(), 1e-15);
}

TEST(SceneIntegrator, SamplesPerPixelOverrideCapsAdaptiveIntegrators) {
  const std::string sensor =
      R"(<sensor type="perspective"><float name="fov" value="40"/>
         <sampler type="independent"><integer name="sample_count" value="64"/></sampler>
         </sensor>)";
  SceneDescription path = parse(sensor + R"(<integrator type="path"/>)");
  overrideSamplesPerPixel(path, 8);
  EXPECT_EQ(path.sensor.sampler.sampleCount, 8);
  overrideSamplesPerPixel(path, 1);
  EXPECT_EQ(path.sensor.sampler.sampleCount, 1);
  EXPECT_THROW(overrideSamplesPerPixel(path, 0), Error);

  const std::string adaptive = sensor + R"(<integrator type="adaptive">
      <integer name="min_samples" value="16"/><integer name="max_samples" value="500"/>
      <integrator type="path"/></integrator>)";
  SceneDescription a = parse(adaptive);
  overrideSamplesPerPixel(a, 100);
  ASSERT_TRUE(a.integrator.as<AdaptiveIntegratorParams>());
  EXPECT_EQ(a.integrator.as<AdaptiveIntegratorParams>()->maxSamples, 100);
  EXPECT_EQ(a.integrator.as<AdaptiveIntegratorParams>()->minSamples, 16);
  overrideSamplesPerPixel(a, 4);
  EXPECT_EQ(a.integrator.as<AdaptiveIntegratorParams>()->maxSamples, 4);
  EXPECT_EQ(a.integrator.as<AdaptiveIntegratorParams>()->minSamples, 4);
  EXPECT_EQ(a.sensor.sampler.sampleCount, 4);
  EXPECT_THROW(overrideSamplesPerPixel(a, 1), Error);
}

TEST(SceneDefaults, NamesOfTheDefaultsAreRecorded) {
  const SceneDescription d = parse(
      std::string(R"(<default name="res" value="64"/><default name="spp" value="4"/>)") + kSensor,
      {{"spp", "8"}});
  EXPECT_EQ(d.defaultNames, (std::vector<std::string>{"res", "spp"}));
}

TEST(SceneIntegrator, EveryTypeAndItsParameters) {
  const std::string sensor =
      R"(<sensor type="perspective"><float name="fov" value="40"/>
         <sampler type="independent"><integer name="sample_count" value="500"/></sampler>
         </sensor>)";
  IntegratorDesc i = parse(sensor + R"(<integrator type="path">
      <integer name="max_depth" value="8"/><integer name="rr_depth" value="3"/>
      <boolean name="hide_emitters" value="true"/></integrator>)")
                         .integrator;
  EXPECT_EQ(i.type, "path");
  ASSERT_TRUE(i.as<PathIntegratorParams>());
  EXPECT_EQ(i.as<PathIntegratorParams>()->path.maxDepth, 8);
  EXPECT_EQ(i.as<PathIntegratorParams>()->path.rrDepth, 3);
  EXPECT_TRUE(i.as<PathIntegratorParams>()->path.hideEmitters);

  i = parse(sensor + R"(<integrator type="direct"><integer name="shading_samples" value="4"/>
      <integer name="bsdf_samples" value="2"/></integrator>)")
          .integrator;
  EXPECT_EQ(i.type, "direct");
  ASSERT_TRUE(i.as<DirectIntegratorParams>());
  EXPECT_EQ(i.as<DirectIntegratorParams>()->emitterSamples, 4);
  EXPECT_EQ(i.as<DirectIntegratorParams>()->bsdfSamples, 2);

  const IntegratorDesc normals = parse(sensor + R"(<integrator type="normals"/>)").integrator;
  EXPECT_EQ(normals.type, "normals");
  EXPECT_TRUE(normals.as<NormalsIntegratorParams>());

  i = parse(sensor + R"(<integrator type="adaptive"><float name="threshold" value="0.02"/>
      <integrator type="path"><integer name="max_depth" value="12"/></integrator>
      </integrator>)")
          .integrator;
  EXPECT_EQ(i.type, "adaptive");
  const AdaptiveIntegratorParams* adaptive = i.as<AdaptiveIntegratorParams>();
  ASSERT_TRUE(adaptive);
  EXPECT_DOUBLE_EQ(adaptive->threshold, 0.02);
  EXPECT_EQ(adaptive->minSamples, 16);
  EXPECT_EQ(adaptive->maxSamples, 500);  // the sampler's sample_count
  EXPECT_EQ(adaptive->path.maxDepth, 12);
  i = parse(sensor + R"(<integrator type="adaptive"><integer name="min_samples" value="8"/>
      <integer name="max_samples" value="100"/></integrator>)")
          .integrator;
  adaptive = i.as<AdaptiveIntegratorParams>();
  ASSERT_TRUE(adaptive);
  EXPECT_EQ(adaptive->minSamples, 8);
  EXPECT_EQ(adaptive->maxSamples, 100);
  EXPECT_DOUBLE_EQ(adaptive->threshold, 0.05);
}

TEST(SceneBsdf, EveryTypeAndRef) {
  const SceneDescription s = parse(std::string(kSensor) + R"(
    <bsdf type="diffuse" id="blue"><rgb name="reflectance" value="0.2, 0.25, 0.7"/></bsdf>
    <bsdf type="diffuse" id="grey"><float name="reflectance" value="0.3"/></bsdf>
    <bsdf type="dielectric" id="glass"><string name="int_ior" value="bk7"/>
      <float name="ext_ior" value="1.0"/></bsdf>
    <bsdf type="conductor" id="gold"><string name="material" value="Au"/></bsdf>
    <bsdf type="conductor" id="metal"><rgb name="eta" value="0.2, 0.9, 1.1"/>
      <rgb name="k" value="3.9, 2.4, 2.2"/></bsdf>
    <bsdf type="roughconductor" id="rough"><string name="distribution" value="ggx"/>
      <float name="alpha" value="0.25"/></bsdf>
    <bsdf type="twosided" id="both"><ref id="blue"/></bsdf>
    <shape type="cube"><ref id="gold"/></shape>
    <shape type="cube"><bsdf type="twosided"><bsdf type="diffuse"/></bsdf></shape>)");
  ASSERT_GE(s.bsdfs.size(), 9u);
  const BsdfDesc& blue = s.bsdfs[0];
  EXPECT_EQ(blue.id, "blue");
  ASSERT_TRUE(blue.as<DiffuseBsdfParams>());
  EXPECT_LT((blue.as<DiffuseBsdfParams>()->reflectance - Color(0.2, 0.25, 0.7)).abs().maxCoeff(),
            1e-15);
  EXPECT_TRUE((s.bsdfs[1].as<DiffuseBsdfParams>()->reflectance == 0.3).all());
  EXPECT_EQ(s.bsdfs[2].type, "dielectric");
  const DielectricBsdfParams* glass = s.bsdfs[2].as<DielectricBsdfParams>();
  ASSERT_TRUE(glass);
  EXPECT_EQ(std::get<std::string>(glass->intIor), "bk7");
  EXPECT_DOUBLE_EQ(std::get<double>(glass->extIor), 1.0);
  ASSERT_TRUE(s.bsdfs[3].as<ConductorBsdfParams>());
  EXPECT_EQ(s.bsdfs[3].as<ConductorBsdfParams>()->conductor.material, "Au");
  const ConductorSpec& metal = s.bsdfs[4].as<ConductorBsdfParams>()->conductor;
  EXPECT_EQ(metal.material, "none");
  EXPECT_DOUBLE_EQ(metal.eta[1], 0.9);
  EXPECT_DOUBLE_EQ(metal.k[0], 3.9);
  EXPECT_EQ(s.bsdfs[5].type, "roughconductor");
  ASSERT_TRUE(s.bsdfs[5].as<RoughConductorBsdfParams>());
  EXPECT_DOUBLE_EQ(s.bsdfs[5].as<RoughConductorBsdfParams>()->alpha, 0.25);
  EXPECT_EQ(s.bsdfs[6].type, "twosided");
  EXPECT_EQ(s.bsdfs[6].params->nested(), 0u);
  ASSERT_EQ(s.shapes.size(), 2u);
  EXPECT_EQ(s.shapes[0].bsdf, 3u);
  // A nested twosided: its inner BSDF is stored before it.
  const BsdfDesc& outer = s.bsdfs.at(s.shapes[1].bsdf);
  ASSERT_EQ(outer.type, "twosided");
  ASSERT_TRUE(outer.params->nested());
  EXPECT_LT(*outer.params->nested(), s.shapes[1].bsdf);
  EXPECT_EQ(s.bsdfs[*outer.params->nested()].type, "diffuse");
}

TEST(SceneEmitter, PointConstantAndArea) {
  const SceneDescription s = parse(std::string(kSensor) + R"(
    <emitter type="point"><rgb name="intensity" value="5, 6, 7"/>
      <point name="position" x="0" y="1.9" z="0.5"/></emitter>
    <emitter type="point"><float name="intensity" value="2"/>
      <transform name="to_world"><translate x="3" y="4"/></transform></emitter>
    <emitter type="constant"><rgb name="radiance" value="0.5"/></emitter>
    <shape type="rectangle"><emitter type="area"><rgb name="radiance" value="10, 9, 8"/>
      </emitter></shape>)");
  ASSERT_EQ(s.emitters.size(), 3u);
  EXPECT_EQ(s.emitters[0].type, "point");
  const PointEmitterParams* p0 = s.emitters[0].as<PointEmitterParams>();
  const PointEmitterParams* p1 = s.emitters[1].as<PointEmitterParams>();
  ASSERT_TRUE(p0 && p1);
  EXPECT_LT((p0->intensity - Color(5, 6, 7)).abs().maxCoeff(), 1e-15);
  EXPECT_LT((p0->position - Vec3(0, 1.9, 0.5)).norm(), 1e-15);
  EXPECT_TRUE((p1->intensity == 2.0).all());
  EXPECT_LT((p1->position - Vec3(3, 4, 0)).norm(), 1e-15);
  EXPECT_EQ(s.emitters[2].type, "constant");
  ASSERT_TRUE(s.emitters[2].as<ConstantEmitterParams>());
  EXPECT_TRUE((s.emitters[2].as<ConstantEmitterParams>()->radiance == 0.5).all());
  ASSERT_EQ(s.shapes.size(), 1u);
  ASSERT_TRUE(s.shapes[0].areaRadiance);
  EXPECT_LT((*s.shapes[0].areaRadiance - Color(10, 9, 8)).abs().maxCoeff(), 1e-15);
}

TEST(SceneShape, MeshAndBuiltinShapes) {
  const TempFolder dir;
  dir.write("meshes/tri.obj", kTriangleObj);
  const fs::path xml = dir.write("scene.xml", std::string("<scene version=\"3.0.0\">") + kSensor +
                                                  R"(
    <shape type="obj" id="tri">
      <string name="filename" value="meshes/tri.obj"/>
      <string name="model" value="flat"/> <string name="tessellation" value="thesis"/>
      <boolean name="face_normals" value="true"/> <boolean name="flip_normals" value="true"/>
    </shape>
    <shape type="obj"><string name="filename" value="meshes/tri.obj"/></shape>
    <shape type="sphere"><point name="center" value="1, 2, 3"/><float name="radius" value="0.5"/>
    </shape>
    <shape type="rectangle"/>
  </scene>)");
  const SceneDescription s = loadSceneDescription(xml);
  ASSERT_EQ(s.shapes.size(), 4u);
  const ShapeDesc& tri = s.shapes[0];
  EXPECT_EQ(tri.type, "obj");
  EXPECT_EQ(tri.id, "tri");
  const MeshFileShapeParams* file = tri.as<MeshFileShapeParams>();
  ASSERT_TRUE(file);
  EXPECT_TRUE(fs::equivalent(file->filename, dir.path() / "meshes/tri.obj"));
  EXPECT_EQ(file->model, "flat");
  EXPECT_EQ(file->tessellation, "thesis");
  EXPECT_TRUE(file->faceNormals);
  EXPECT_TRUE(tri.flipNormals);
  EXPECT_EQ(tri.location, xml.string() + ":2");
  const MeshFileShapeParams* plain = s.shapes[1].as<MeshFileShapeParams>();
  ASSERT_TRUE(plain);
  EXPECT_EQ(plain->model, "shading");
  EXPECT_TRUE(plain->tessellation.empty());
  EXPECT_FALSE(plain->faceNormals);
  EXPECT_EQ(s.shapes[2].type, "sphere");
  EXPECT_EQ(s.shapes[3].type, "rectangle");
  // The sphere's center and radius become its transform of the unit sphere.
  const Mat4& sphere = s.shapes[2].toWorld;
  EXPECT_LT((apply(sphere, Vec3(0, 0, 1)) - Vec3(1, 2, 3.5)).norm(), 1e-15);
  // Shapes without a BSDF share one default diffuse 0.5.
  EXPECT_EQ(s.shapes[0].bsdf, s.shapes[3].bsdf);
  const BsdfDesc& fallback = s.bsdfs.at(s.shapes[3].bsdf);
  EXPECT_EQ(fallback.type, "diffuse");
  ASSERT_TRUE(fallback.as<DiffuseBsdfParams>());
  EXPECT_TRUE((fallback.as<DiffuseBsdfParams>()->reflectance == 0.5).all());
}

TEST(SceneParameters, SubstitutionAndCommandLinePrecedence) {
  const std::string body = std::string(R"(<default name="spp" value="16"/>
    <default name="fov" value="30"/>
    <sensor type="perspective"><float name="fov" value="$fov"/>
      <sampler type="independent"><integer name="sample_count" value="$spp"/></sampler>
    </sensor>
    <shape type="cube"><bsdf type="diffuse"><rgb name="reflectance" value="$r, 0.5, $r"/></bsdf>
    </shape>)");
  const SceneDescription fromDefaults = parse(body, {{"r", "0.25"}});
  EXPECT_EQ(fromDefaults.sensor.sampler.sampleCount, 16);
  EXPECT_DOUBLE_EQ(fromDefaults.sensor.fov, 30.0);
  EXPECT_LT((fromDefaults.bsdfs.at(0).as<DiffuseBsdfParams>()->reflectance - Color(0.25, 0.5, 0.25))
                .abs()
                .maxCoeff(),
            1e-15);
  // -D wins over <default>.
  const SceneDescription overridden = parse(body, {{"spp", "256"}, {"r", "0.1"}});
  EXPECT_EQ(overridden.sensor.sampler.sampleCount, 256);
  EXPECT_DOUBLE_EQ(overridden.sensor.fov, 30.0);
  // An undefined name is an error naming it.
  const std::string message = errorOf("<scene version=\"3.0.0\">\n" + body + "</scene>");
  EXPECT_NE(message.find("test.xml:7:"), std::string::npos) << message;
  EXPECT_NE(message.find("$r"), std::string::npos) << message;
}

TEST(SceneInclude, IncludedFileAddsObjectsAndReportsItsOwnLines) {
  const TempFolder dir;
  dir.write("parts/materials.xml", R"(<scene version="3.0.0">
    <bsdf type="diffuse" id="red"><rgb name="reflectance" value="0.8, 0.1, 0.1"/></bsdf>
  </scene>)");
  const fs::path broken = dir.write("parts/broken.xml",
                                    "<scene version=\"3.0.0\">\n\n"
                                    "<shape type=\"torus\"/>\n</scene>");
  const fs::path main = dir.write("main.xml", std::string("<scene version=\"3.0.0\">") + kSensor +
                                                  R"(<include filename="parts/materials.xml"/>
    <shape type="cube"><ref id="red"/></shape></scene>)");
  const SceneDescription s = loadSceneDescription(main);
  ASSERT_EQ(s.shapes.size(), 1u);
  EXPECT_DOUBLE_EQ(s.bsdfs.at(s.shapes[0].bsdf).as<DiffuseBsdfParams>()->reflectance[0], 0.8);
  const std::string message =
      errorOf("<scene version=\"3.0.0\"><include filename=\"parts/broken.xml\"/></scene>", main);
  EXPECT_NE(message.find(broken.string() + ":3:"), std::string::npos) << message;
  EXPECT_NE(message.find("torus"), std::string::npos) << message;
}

TEST(SceneToString, NamesTypeParametersAndLocation) {
  const SceneDescription s = parse(std::string(kSensor) +
                                   R"(<bsdf type="dielectric"><float name="int_ior" value="1.5"/>
                                      </bsdf>)");
  const std::string text = toString(s.bsdfs.at(0));
  EXPECT_NE(text.find("dielectric"), std::string::npos) << text;
  EXPECT_NE(text.find("int_ior=1.5"), std::string::npos) << text;
  EXPECT_NE(text.find("test.xml:1"), std::string::npos) << text;
  EXPECT_NE(toString(s.sensor).find("fov=40"), std::string::npos) << toString(s.sensor);
}

struct ErrorCase {
  const char* what;
  std::string xml;      // line 1 is always <scene ...>
  const char* where;    // "test.xml:LINE:"
  const char* mention;  // the offending name
};

TEST(SceneErrors, EachNamesFileLineAndOffender) {
  const std::string head = "<scene version=\"3.0.0\">\n";
  const std::string sensor = std::string(kSensor) + "\n";
  const std::vector<ErrorCase> cases = {
      {"xml syntax", head + sensor + "<shape type=\"cube\">\n</scene>", "test.xml:4:", "XML"},
      {"unknown element", head + sensor + "<texture type=\"bitmap\"/>\n</scene>",
       "test.xml:3:", "texture"},
      {"unknown attribute",
       head + "<sensor type=\"perspective\">\n<float name=\"fov\" value=\"4\" units=\"deg\"/>"
              "</sensor></scene>",
       "test.xml:3:", "units"},
      {"unknown property",
       head + "<sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/>\n"
              "<float name=\"fvo\" value=\"4\"/></sensor></scene>",
       "test.xml:3:", "fvo"},
      {"wrong type",
       head + "<sensor type=\"perspective\">\n\n<string name=\"fov\" value=\"40\"/></sensor>"
              "</scene>",
       "test.xml:4:", "fov"},
      {"malformed number",
       head + "<sensor type=\"perspective\">\n<float name=\"fov\" value=\"4o\"/></sensor></scene>",
       "test.xml:3:", "4o"},
      {"missing required",
       head + "\n<sensor type=\"perspective\"><float name=\"near_clip\" value=\"1\"/></sensor>"
              "</scene>",
       "test.xml:3:", "fov"},
      {"missing file",
       head + sensor +
           "<shape type=\"ply\">\n<string name=\"filename\" value=\"nope.ply\"/>"
           "</shape></scene>",
       "test.xml:4:", "nope.ply"},
      {"unknown ref", head + sensor + "<shape type=\"cube\">\n<ref id=\"chrome\"/></shape></scene>",
       "test.xml:4:", "chrome"},
      {"beckmann",
       head + sensor +
           "<bsdf type=\"roughconductor\">\n<string name=\"distribution\" "
           "value=\"beckmann\"/></bsdf></scene>",
       "test.xml:4:", "not supported"},
      {"unknown model",
       head + sensor +
           "<shape type=\"cube\"/>\n<shape type=\"obj\">\n"
           "<string name=\"model\" value=\"bezier\"/>"
           "<string name=\"filename\" value=\"CMakeLists.txt\"/></shape></scene>",
       "test.xml:5:", "bezier"},
      {"unknown plugin type", head + sensor + "\n<bsdf type=\"plastic\"/></scene>",
       "test.xml:4:", "plastic"},
      {"area emitter outside a shape", head + sensor + "<emitter type=\"area\"/></scene>",
       "test.xml:3:", "area"},
      {"duplicate property",
       head + "<sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/>\n"
              "<float name=\"fov\" value=\"50\"/></sensor></scene>",
       "test.xml:3:", "fov"},
      {"bad transform child",
       head + sensor +
           "<shape type=\"cube\"><transform name=\"to_world\">\n"
           "<shear value=\"1\"/></transform></shape></scene>",
       "test.xml:4:", "shear"},
      {"bad enum",
       head + "<sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/>\n"
              "<string name=\"fov_axis\" value=\"z\"/></sensor></scene>",
       "test.xml:3:", "fov_axis"},
      {"missing sensor", head + "<shape type=\"cube\"/></scene>", "test.xml:1:", "sensor"},
      {"old version", "<scene version=\"0.6.0\">" + sensor + "</scene>", "test.xml:1:", "0.6.0"},
  };
  for (const ErrorCase& c : cases) {
    // The scene "lives" in tests/, so that a mesh filename can name an existing file.
    const std::string message = errorOf(c.xml, fs::path(QUADTRI_TEST_DIR) / "test.xml");
    // Messages start with the file's path; compare from its name on.
    const size_t at = message.find(c.where);
    EXPECT_NE(at, std::string::npos) << c.what << ": " << message;
    EXPECT_EQ(message.find(": ", at), at + std::string(c.where).size() - 1)
        << c.what << ": " << message;
    EXPECT_NE(message.find(c.mention), std::string::npos) << c.what << ": " << message;
  }
}

TEST(SceneParameters, DefineWithoutDefault) {
  // A define reaches attributes even without a <default>.
  const SceneDescription s =
      parse(R"(<sensor type="perspective"><float name="fov" value="$f"/></sensor>)", {{"f", "12"}});
  EXPECT_DOUBLE_EQ(s.sensor.fov, 12.0);
}

}  // namespace
}  // namespace quadtri
