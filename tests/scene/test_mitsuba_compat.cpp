// Mitsuba 3 scenes as users have them: every documented property of the supported plugins is
// accepted — honoured where it changes the image (crop window, principal point, focal length,
// spectra), noted where it does not (pixel_format, focus_distance on a pinhole, ...), and an
// error where quadtri cannot honour it (anisotropic roughness, tinted specular reflectance).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "quadtri/math/error.h"
#include "quadtri/render/integrator/path_integrator.h"
#include "quadtri/render/renderer.h"
#include "quadtri/scene/bsdf/diffuse_xml.h"
#include "quadtri/scene/bsdf/rough_conductor_xml.h"
#include "quadtri/scene/emitter/constant_xml.h"
#include "quadtri/scene/scene_builder.h"
#include "quadtri/scene/scene_loader.h"
#include "quadtri/scene/spectrum.h"

namespace quadtri {
namespace {

SceneDescription parse(const std::string& body) {
  return parseSceneDescription("<scene version=\"3.0.0\">" + body + "</scene>", "test.xml");
}

std::string errorOf(const std::string& body) {
  try {
    parse(body);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

bool mentions(const std::vector<std::string>& notes, const std::string& what) {
  for (const std::string& n : notes)
    if (n.find(what) != std::string::npos) return true;
  return false;
}

// The sensor of Mitsuba's own Cornell box (mitsuba-data scenes/cbox/cbox_rgb.xml), whose
// pixel_format, component_format and focus_distance used to be errors.
constexpr const char* kCboxSensor = R"(
  <sensor type="perspective" id="sensor">
    <string name="fov_axis" value="smaller"/>
    <float name="near_clip" value="0.001"/>
    <float name="far_clip" value="100.0"/>
    <float name="focus_distance" value="1000"/>
    <float name="fov" value="39.3077"/>
    <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
    <sampler type="independent"><integer name="sample_count" value="16"/></sampler>
    <film type="hdrfilm">
      <integer name="width" value="64"/> <integer name="height" value="48"/>
      <rfilter type="tent"/>
      <string name="pixel_format" value="rgb"/>
      <string name="component_format" value="float32"/>
      <string name="file_format" value="openexr"/>
      <boolean name="sample_border" value="true"/>
      <boolean name="compensate" value="false"/>
    </film>
  </sensor>)";

TEST(MitsubaCompat, CornellBoxSensorLoadsWithOneNotePerIgnoredProperty) {
  const SceneDescription scene = parse(kCboxSensor);
  EXPECT_EQ(scene.sensor.film.width, 64);
  EXPECT_NEAR(scene.sensor.fov, 39.3077, 1e-12);
  EXPECT_EQ(scene.sensor.film.filter.type, FilterDesc::Type::Tent);
  EXPECT_EQ(scene.sensor.film.filter.radius, 1.0);
  ASSERT_EQ(scene.notes.size(), 6u);
  for (const char* name : {"focus_distance", "pixel_format", "component_format", "file_format",
                           "sample_border", "compensate"})
    EXPECT_TRUE(mentions(scene.notes, name)) << name;
  // Each note names the file and the line of the property.
  EXPECT_TRUE(mentions(scene.notes, "test.xml:6: note: sensor 'perspective': focus_distance"));
}

TEST(MitsubaCompat, EveryDocumentedSensorPropertyIsAccepted) {
  const SceneDescription scene = parse(R"(
    <sensor type="perspective">
      <string name="focal_length" value="50mm"/>
      <float name="near_clip" value="0.1"/> <float name="far_clip" value="50"/>
      <float name="principal_point_offset_x" value="0.1"/>
      <float name="principal_point_offset_y" value="-0.05"/>
      <float name="shutter_open" value="0"/> <float name="shutter_close" value="0"/>
      <film type="hdrfilm">
        <integer name="width" value="40"/> <integer name="height" value="30"/>
        <integer name="crop_offset_x" value="5"/> <integer name="crop_offset_y" value="6"/>
        <integer name="crop_width" value="20"/> <integer name="crop_height" value="10"/>
      </film>
      <sampler type="stratified"><integer name="sample_count" value="4"/>
        <boolean name="jitter" value="true"/></sampler>
    </sensor>)");
  // 50 mm on 35 mm film is a diagonal field of view of 2·atan(43.267 / 100) = 46.793°.
  EXPECT_NEAR(scene.sensor.fov, 2.0 * std::atan(std::hypot(36.0, 24.0) / 100.0) * 180.0 / kPi,
              1e-12);
  EXPECT_NEAR(scene.sensor.fov, 46.793, 1e-3);
  EXPECT_EQ(scene.sensor.fovAxis, FovAxis::Diagonal);
  EXPECT_EQ(scene.sensor.principalPointOffset, Vec2(0.1, -0.05));
  EXPECT_EQ(scene.sensor.film.cropX, 5);
  EXPECT_EQ(scene.sensor.film.cropY, 6);
  EXPECT_EQ(scene.sensor.film.cropWidth, 20);
  EXPECT_EQ(scene.sensor.film.cropHeight, 10);
  EXPECT_EQ(scene.sensor.sampler.sampleCount, 4);
  EXPECT_TRUE(mentions(scene.notes, "sampler 'stratified' is sampled as 'independent'"));
  EXPECT_TRUE(mentions(scene.notes, "shutter_open"));
  EXPECT_TRUE(mentions(scene.notes, "jitter"));
}

TEST(MitsubaCompat, CropAndSensorErrorsNameTheProperty) {
  const auto film = [](const std::string& props) {
    return "<sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/><film "
           "type=\"hdrfilm\"><integer name=\"width\" value=\"40\"/><integer name=\"height\" "
           "value=\"30\"/>" +
           props + "</film></sensor>";
  };
  EXPECT_NE(errorOf(film("<integer name=\"crop_offset_x\" value=\"40\"/>")).find("crop_offset_x"),
            std::string::npos);
  EXPECT_NE(errorOf(film("<integer name=\"crop_offset_y\" value=\"10\"/><integer "
                         "name=\"crop_height\" value=\"21\"/>"))
                .find("crop_height must be in [1, height - crop_offset_y = 20], got 21"),
            std::string::npos);
  EXPECT_NE(errorOf("<sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/><string "
                    "name=\"focal_length\" value=\"35mm\"/></sensor>")
                .find("focal_length and fov both given"),
            std::string::npos);
  EXPECT_NE(errorOf("<sensor type=\"perspective\"><string name=\"focal_length\" "
                    "value=\"wide\"/></sensor>")
                .find("'wide' is not a length"),
            std::string::npos);
  EXPECT_NE(errorOf("<sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/><sampler "
                    "type=\"sobol\"/></sensor>")
                .find("unknown sampler type 'sobol'"),
            std::string::npos);
}

TEST(MitsubaCompat, SpectraBecomeRgb) {
  // A flat spectrum is the grey of its value, whether written as one value or as pairs.
  const SceneDescription scene =
      parse(std::string(R"(<sensor type="perspective"><float name="fov" value="40"/></sensor>
    <bsdf type="diffuse" id="one"><spectrum name="reflectance" value="0.4"/></bsdf>
    <bsdf type="diffuse" id="flat"><spectrum name="reflectance" value="400:0.4, 500:0.4, 700:0.4"/></bsdf>
    <bsdf type="diffuse" id="red"><spectrum name="reflectance" value="380:0.05, 580:0.05, 600:0.9, 780:0.9"/></bsdf>
    <emitter type="constant"><spectrum name="radiance" value="1.5"/></emitter>)"));
  ASSERT_EQ(scene.bsdfs.size(), 3u);
  EXPECT_NEAR(
      (scene.bsdfs[0].as<DiffuseBsdfParams>()->reflectance - Color::Constant(0.4)).abs().maxCoeff(),
      0.0, 1e-15);
  EXPECT_NEAR(
      (scene.bsdfs[1].as<DiffuseBsdfParams>()->reflectance - Color::Constant(0.4)).abs().maxCoeff(),
      0.0, 1e-12);
  // A spectrum that reflects only above 590 nm is red: far more red than green or blue.
  const Color red = scene.bsdfs[2].as<DiffuseBsdfParams>()->reflectance;
  EXPECT_GT(red[0], 0.6);
  EXPECT_LT(red[1], 0.35);
  EXPECT_LT(red[2], 0.15);
  EXPECT_NEAR(scene.emitters[0].as<ConstantEmitterParams>()->radiance[1], 1.5, 1e-15);
}

TEST(MitsubaCompat, MatchingFunctionsHaveTheCieIntegrals) {
  // The tabulated CIE 1931 2° functions integrate to 106.857 (x̄), 106.857 (ȳ), 106.892 (z̄)
  // over 360–830 nm at 1 nm; the Wyman–Sloan–Shirley fit is within 1.5% of each.
  Color sum = Color::Zero();
  for (double nm = 360.5; nm < 830.0; nm += 1.0) sum += cieXyzMatching(nm);
  EXPECT_NEAR(sum[0] / 106.857, 1.0, 0.015);
  EXPECT_NEAR(sum[1] / 106.857, 1.0, 0.015);
  EXPECT_NEAR(sum[2] / 106.892, 1.0, 0.015);
  // ȳ peaks at 555 nm (the photopic peak) with a value near 1.
  EXPECT_NEAR(cieXyzMatching(555.0)[1], 1.0, 0.01);
  EXPECT_GT(cieXyzMatching(555.0)[1], cieXyzMatching(530.0)[1]);
  EXPECT_GT(cieXyzMatching(555.0)[1], cieXyzMatching(580.0)[1]);
}

TEST(MitsubaCompat, SpectrumErrorsNameTheValue) {
  const std::string head =
      "<sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/></sensor>";
  EXPECT_NE(errorOf(head + "<bsdf type=\"diffuse\"><spectrum name=\"reflectance\" "
                           "value=\"500:0.5, 400:0.5\"/></bsdf>")
                .find("wavelengths must increase: 400 nm follows 500 nm"),
            std::string::npos);
  EXPECT_NE(errorOf(head + "<bsdf type=\"diffuse\"><spectrum name=\"reflectance\" "
                           "filename=\"data.spd\"/></bsdf>")
                .find("spectral data file) is not supported"),
            std::string::npos);
  EXPECT_NE(errorOf(head + "<bsdf type=\"diffuse\"><spectrum name=\"reflectance\" "
                           "value=\"500:0.5, 600\"/></bsdf>")
                .find("'600' is not wavelength:value"),
            std::string::npos);
}

TEST(MitsubaCompat, EveryDocumentedBsdfEmitterAndShapePropertyIsAccepted) {
  const SceneDescription scene =
      parse(R"(<sensor type="perspective"><float name="fov" value="40"/></sensor>
    <bsdf type="dielectric"><float name="int_ior" value="1.5"/><float name="ext_ior" value="1.0"/>
      <rgb name="specular_reflectance" value="1"/><rgb name="specular_transmittance" value="1"/></bsdf>
    <bsdf type="conductor"><string name="material" value="Au"/><rgb name="specular_reflectance" value="1"/></bsdf>
    <bsdf type="roughconductor"><string name="distribution" value="ggx"/>
      <float name="alpha_u" value="0.2"/><float name="alpha_v" value="0.2"/>
      <boolean name="sample_visible" value="true"/><string name="material" value="Cu"/></bsdf>
    <emitter type="point"><point name="position" value="0, 1, 0"/><float name="sampling_weight" value="2"/></emitter>
    <emitter type="constant"><rgb name="radiance" value="0.1"/><float name="sampling_weight" value="1"/></emitter>
    <shape type="sphere"><point name="center" value="0, 0, 0"/><float name="radius" value="1"/>
      <boolean name="flip_normals" value="false"/>
      <emitter type="area"><rgb name="radiance" value="1"/><float name="sampling_weight" value="1"/></emitter></shape>)");
  ASSERT_EQ(scene.bsdfs.size(), 4u);  // three, and the default one of the sphere
  EXPECT_DOUBLE_EQ(scene.bsdfs[2].as<RoughConductorBsdfParams>()->alpha, 0.2);
  EXPECT_TRUE(mentions(scene.notes, "sample_visible"));
  EXPECT_TRUE(mentions(scene.notes, "emitter 'point': sampling_weight"));
  EXPECT_TRUE(mentions(scene.notes, "emitter 'area': sampling_weight"));
}

TEST(MitsubaCompat, PropertiesQuadtriCannotHonourAreErrors) {
  const std::string head =
      "<sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/></sensor>";
  EXPECT_NE(errorOf(head + "<bsdf type=\"roughconductor\"><string name=\"distribution\" "
                           "value=\"ggx\"/><float name=\"alpha_u\" value=\"0.1\"/><float "
                           "name=\"alpha_v\" value=\"0.3\"/></bsdf>")
                .find("0.1 differs from alpha_v 0.3; quadtri's GGX is isotropic"),
            std::string::npos);
  EXPECT_NE(errorOf(head + "<bsdf type=\"conductor\"><rgb name=\"specular_reflectance\" "
                           "value=\"0.5\"/></bsdf>")
                .find("specular_reflectance 0.5, 0.5, 0.5 is not supported"),
            std::string::npos);
}

// A crop window renders exactly the pixels of the full render inside it: the pixel streams
// are keyed by the pixel's position on the whole film.
TEST(MitsubaCompat, CropWindowIsBitwiseTheSameWindowOfTheFullRender) {
  const std::string scene = std::string(R"(
    <sensor type="perspective"><float name="fov" value="45"/>
      <transform name="to_world"><lookat origin="0, 0, 3.5" target="0, 0, 0" up="0, 1, 0"/></transform>
      <film type="hdrfilm"><integer name="width" value="24"/><integer name="height" value="18"/>CROP</film>
      <sampler type="independent"><integer name="sample_count" value="3"/><integer name="seed" value="7"/></sampler>
    </sensor>
    <shape type="sphere"><bsdf type="diffuse"/></shape>
    <emitter type="point"><point name="position" value="2, 3, 2"/><rgb name="intensity" value="10"/></emitter>
    <emitter type="constant"><rgb name="radiance" value="0.3"/></emitter>)");
  const auto renderWith = [&](const std::string& crop) {
    std::string xml = scene;
    xml.replace(xml.find("CROP"), 4, crop);
    const BuiltScene built = buildScene(parse(xml), std::nullopt);
    RenderOptions options = built.options;
    options.threads = 1;
    return render(*built.scene, *built.integrator, options).image;
  };
  const Image full = renderWith("");
  const Image window = renderWith(
      "<integer name=\"crop_offset_x\" value=\"5\"/><integer name=\"crop_offset_y\" "
      "value=\"7\"/><integer name=\"crop_width\" value=\"11\"/><integer name=\"crop_height\" "
      "value=\"6\"/>");
  ASSERT_EQ(window.width, 11);
  ASSERT_EQ(window.height, 6);
  size_t lit = 0;
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 11; ++x) {
      const Color& a = window.pixels[size_t(y) * 11 + size_t(x)];
      const Color& b = full.pixels[size_t(y + 7) * 24 + size_t(x + 5)];
      ASSERT_TRUE((a == b).all()) << "pixel " << x << "," << y << ": " << a.transpose() << " vs "
                                  << b.transpose();
      lit += std::abs(a[0] - 0.3) > 1e-3;  // not the sky
    }
  EXPECT_GT(lit, 0u);  // the window shows the lit sphere, not only the sky
}

// The principal point is where the optical axis meets the film.
TEST(MitsubaCompat, PrincipalPointOffsetMovesTheOpticalAxis) {
  PerspectiveCamera::Params p;
  p.width = 200;
  p.height = 100;
  p.fovDegrees = 50;
  p.principalPointOffset = Vec2(0.1, -0.2);
  const PerspectiveCamera camera(p);
  // (0.5 + 0.1)·200 = 120, (0.5 − 0.2)·100 = 30: the ray there runs along the camera's +z.
  const Ray axis = camera.generateRay(Vec2(120, 30));
  EXPECT_NEAR((axis.direction - Vec3(0, 0, 1)).norm(), 0.0, 1e-12);
  // The field of view keeps its size: 100 pixels to the left is still fov/2 off the axis.
  const Ray edge = camera.generateRay(Vec2(20, 30));
  EXPECT_NEAR(std::acos(edge.direction.z()) * 180.0 / kPi, 25.0, 1e-9);
}

}  // namespace
}  // namespace quadtri
