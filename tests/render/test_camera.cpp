// The perspective camera's Mitsuba conventions, the reconstruction filters and image output.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "quadtri/io/image_module.h"
#include "quadtri/math/error.h"
#include "quadtri/render/camera.h"
#include "quadtri/render/filter.h"
#include "quadtri/render/image_io.h"
#include "render/chi2.h"
#include "render_fixtures.h"

namespace quadtri::testing {
namespace {

double angleBetweenDeg(const Vec3& a, const Vec3& b) {
  return angleDegrees(a, b);
}

TEST(PerspectiveCamera, MitsubaLookAtOrientation) {
  // Looking from +z at the origin with +y up: the image's left edge shows world −x, its top +y.
  const PerspectiveCamera cam = makeCamera(Vec3(0, 0, 5), Vec3::Zero(), 60.0, 40, 20);
  const Ray centre = cam.generateRay(Vec2(20, 10));
  EXPECT_NEAR((centre.direction - Vec3(0, 0, -1)).norm(), 0.0, 1e-12);
  EXPECT_TRUE(centre.origin.isApprox(Vec3(0, 0, 5)));
  EXPECT_LT(cam.generateRay(Vec2(0, 10)).direction.x(), 0.0);
  EXPECT_GT(cam.generateRay(Vec2(40, 10)).direction.x(), 0.0);
  EXPECT_GT(cam.generateRay(Vec2(20, 0)).direction.y(), 0.0);
  // fov is horizontal by default: the left edge is fov/2 off the axis.
  EXPECT_NEAR(angleBetweenDeg(cam.generateRay(Vec2(0, 10)).direction, centre.direction), 30.0,
              1e-9);
}

TEST(PerspectiveCamera, FovAxes) {
  PerspectiveCamera::Params p;
  p.width = 300;
  p.height = 100;
  p.fovDegrees = 40;
  p.fovAxis = FovAxis::Y;
  const PerspectiveCamera y(p);
  EXPECT_NEAR(angleBetweenDeg(y.generateRay(Vec2(150, 0)).direction, Vec3(0, 0, 1)), 20.0, 1e-9);
  p.fovAxis = FovAxis::Diagonal;
  const PerspectiveCamera d(p);
  EXPECT_NEAR(angleBetweenDeg(d.generateRay(Vec2(0, 0)).direction, Vec3(0, 0, 1)), 20.0, 1e-9);
  p.fovAxis = FovAxis::Smaller;  // the vertical one for a wide image
  EXPECT_NEAR(PerspectiveCamera(p).fovXDegrees(), y.fovXDegrees(), 1e-12);
  p.fovAxis = FovAxis::Larger;
  EXPECT_NEAR(PerspectiveCamera(p).fovXDegrees(), 40.0, 1e-12);
}

TEST(PerspectiveCamera, ClipDistancesAlongTheOpticalAxis) {
  PerspectiveCamera::Params p;
  p.nearClip = 0.5;
  p.farClip = 10;
  p.width = p.height = 10;
  p.fovDegrees = 90;
  const PerspectiveCamera cam(p);
  for (const Vec2& film : {Vec2(5, 5), Vec2(0, 0), Vec2(3, 9)}) {
    const Ray r = cam.generateRay(film);
    EXPECT_NEAR(r.tnear * r.direction.z(), 0.5, 1e-12);
    EXPECT_NEAR(r.tfar * r.direction.z(), 10.0, 1e-12);
  }
  p.nearClip = 0;
  EXPECT_THROW(PerspectiveCamera{p}, Error);
}

TEST(ReconstructionFilter, GaussianOffsetsFollowTheTruncatedNormal) {
  ReconstructionFilter filter;  // gaussian, σ = 0.5, radius 2
  Pcg32 rng(3);
  const Chi2Result r = chi2Test(
      20, 20, 200000,
      [&]() -> std::optional<Vec2> {
        return (filter.sampleOffset(rng) / 4.0 + Vec2(0.5, 0.5)).eval();
      },
      [](const Vec2& p) {
        const auto g = [](double t) {
          const double x = 4.0 * (t - 0.5);  // offset in pixels
          return std::exp(-x * x / (2 * 0.25)) /
                 (std::sqrt(2 * kPi) * 0.5 * std::erf(2.0 / (0.5 * std::sqrt(2.0))));
        };
        return 16.0 * g(p.x()) * g(p.y());
      });
  EXPECT_GT(r.pValue, 1e-3) << r.report;
}

TEST(ReconstructionFilter, BoxCoversThePixel) {
  ReconstructionFilter filter;
  filter.kind = ReconstructionFilter::Kind::Box;
  Pcg32 rng(5);
  const Chi2Result r = chi2Test(
      10, 10, 50000,
      [&]() -> std::optional<Vec2> { return (filter.sampleOffset(rng) + Vec2(0.5, 0.5)).eval(); },
      [](const Vec2&) { return 1.0; });
  EXPECT_GT(r.pValue, 1e-3) << r.report;
}

TEST(ReconstructionFilter, TentOffsetsFollowTheTriangle) {
  ReconstructionFilter filter;
  filter.kind = ReconstructionFilter::Kind::Tent;
  filter.tentRadius = 1.5;
  Pcg32 rng(9);
  // Offsets in [−r, r] mapped to [0, 1]: the triangle density 2(1 − 2|t − ½|) per axis.
  const Chi2Result r = chi2Test(
      16, 16, 200000,
      [&]() -> std::optional<Vec2> {
        return (filter.sampleOffset(rng) / (2.0 * filter.tentRadius) + Vec2(0.5, 0.5)).eval();
      },
      [](const Vec2& p) {
        const auto tent = [](double t) { return 2.0 * (1.0 - 2.0 * std::abs(t - 0.5)); };
        return tent(p.x()) * tent(p.y());
      });
  EXPECT_GT(r.pValue, 1e-3) << r.report;
  EXPECT_DOUBLE_EQ(filter.radius(), 1.5);
}

// Whether a shared library whose file name contains `name` is mapped into this process.
bool mapped(const std::string& name) {
  std::ifstream maps("/proc/self/maps");
  std::string line;
  while (std::getline(maps, line))
    if (line.find(name) != std::string::npos) return true;
  return false;
}

// OpenImageIO arrives with the image module only: a program that links quadtri does not load
// it (nor its ~270 libraries) until an image is written. Holds whatever ran before in this
// process: before the write, OpenImageIO is mapped exactly when the module is.
TEST(ImageIo, OpenImageIoIsLoadedOnlyWithTheImageModule) {
  EXPECT_EQ(mapped("libOpenImageIO.so"), mapped("libquadtri_image.so"));
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "quadtri_test_image_module";
  std::filesystem::create_directories(dir);
  Image image(2, 2);
  image.at(1, 1) = Color(0.5, 0.25, 1.0);
  EXPECT_EQ(writeImage(image, dir / "b.exr"), 0u);
  EXPECT_TRUE(mapped("libquadtri_image.so"));
  EXPECT_TRUE(mapped("libOpenImageIO.so"));
  ImageFrame frame;
  const Image back = readImage(dir / "b.exr", &frame);
  ASSERT_EQ(back.pixels.size(), 4u);
  EXPECT_TRUE((back.at(1, 1) == Color(0.5, 0.25, 1.0)).all());
  EXPECT_EQ(frame.filmWidth, 2);
  std::filesystem::remove_all(dir);
}

TEST(ImageIo, SrgbTransferFunction) {
  EXPECT_EQ(linearToSrgb(0.0), 0.0);
  EXPECT_NEAR(linearToSrgb(1.0), 1.0, 1e-15);
  EXPECT_NEAR(linearToSrgb(0.0031308), 12.92 * 0.0031308, 1e-12);
  EXPECT_NEAR(linearToSrgb(0.18), 0.4613561, 1e-6);  // mid grey
  EXPECT_EQ(linearToSrgb(-3.0), 0.0);
  EXPECT_NEAR(linearToSrgb(7.0), 1.0, 1e-15);
}

TEST(ImageIo, WritesExrAndPngWithoutNonFiniteValues) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "quadtri_test_image_io";
  std::filesystem::create_directories(dir);
  Image image(3, 2);
  image.at(0, 0) = Color(0.25, 0.5, 2.0);
  image.at(1, 0) = Color(std::nan(""), 1.0, -kInfinity);
  image.at(2, 1) = Color(0.18, 0.0, 1.0);
  EXPECT_EQ(writeImage(image, dir / "a.exr"), 2u);
  EXPECT_EQ(writeImage(image, dir / "a.png"), 2u);

  ImageFileSpec spec;
  std::vector<float> exr;
  ASSERT_EQ(imageModule().read((dir / "a.exr").string(), spec, exr), "");
  ASSERT_EQ(exr.size(), 18u);
  EXPECT_TRUE(spec.floatPixels);
  EXPECT_EQ(exr[0], 0.25f);
  EXPECT_EQ(exr[2], 2.0f);
  EXPECT_EQ(exr[3], 0.0f);  // NaN written as 0
  EXPECT_EQ(exr[5], 0.0f);  // −∞ written as 0
  EXPECT_FLOAT_EQ(exr[15], 0.18f);

  std::vector<float> png;
  ASSERT_EQ(imageModule().read((dir / "a.png").string(), spec, png), "");
  ASSERT_EQ(png.size(), 18u);
  EXPECT_FALSE(spec.floatPixels);                 // 8-bit, read back as value / 255
  EXPECT_EQ(std::lround(png[2] * 255.0f), 255);   // 2.0 clamps
  EXPECT_EQ(std::lround(png[15] * 255.0f), 118);  // 0.18 → sRGB 0.461 → 118
  EXPECT_THROW(writeImage(image, dir / "a.jpg"), Error);
  EXPECT_FALSE(std::filesystem::exists(dir / "a.jpg"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace quadtri::testing
