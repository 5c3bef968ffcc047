// The tiled renderer: determinism, NaN handling, adaptive sampling and stopping early.
#include <gtest/gtest.h>
#include <xmmintrin.h>

#include <chrono>
#include <thread>

#include "quadtri/render/integrator/adaptive_integrator.h"
#include "quadtri/render/integrator/path_integrator.h"
#include "render_fixtures.h"

namespace quadtri::testing {
namespace {

void furnaceScene(RenderScene& scene, int width, int height) {
  scene.addSphere(Vec3::Zero(), 1.0, Mat4::Identity(), false, diffuse(0.8), std::nullopt, "sphere");
  scene.addPointLight(Vec3(2, 3, 2), Color::Constant(10.0));
  scene.setEnvironment(Color::Constant(0.5));
  scene.setCamera(makeCamera(Vec3(0, 0, 3.5), Vec3::Zero(), 45.0, width, height));
  scene.commit();
}

// The furnace's sphere on a floor of triangles, so that camera rays go through Embree's packets.
void sphereOnFloorScene(RenderScene& scene, int width, int height) {
  scene.addSphere(Vec3::Zero(), 1.0, Mat4::Identity(), false, diffuse(0.8), std::nullopt, "sphere");
  TriangleMesh floor;
  floor.positions = {Vec3(-4, -1.2, -4), Vec3(4, -1.2, -4), Vec3(4, -1.2, 4), Vec3(-4, -1.2, 4)};
  floor.triangles = {{0, 2, 1}, {0, 3, 2}};
  addMesh(scene, std::move(floor), "flat", diffuse(0.5));
  scene.addPointLight(Vec3(2, 3, 2), Color::Constant(10.0));
  scene.setEnvironment(Color::Constant(0.5));
  scene.setCamera(makeCamera(Vec3(0, 0.3, 3.5), Vec3::Zero(), 45.0, width, height));
  scene.commit();
}

TEST(Renderer, ImageDoesNotDependOnThreadCount) {
  // The furnace's sphere on a floor of triangles, so that camera rays go through Embree's
  // packets; the film not a multiple of the tile size.
  RenderScene scene;
  sphereOnFloorScene(scene, 37, 21);
  const PathIntegrator path({});
  RenderOptions options;
  options.samplesPerPixel = 4;
  options.seed = 11;
  options.threads = 1;
  const RenderResult one = render(scene, path, options);
  options.threads = 2;
  const RenderResult two = render(scene, path, options);
  ASSERT_EQ(one.image.pixels.size(), two.image.pixels.size());
  for (size_t i = 0; i < one.image.pixels.size(); ++i)
    ASSERT_TRUE((one.image.pixels[i] == two.image.pixels[i]).all()) << "pixel " << i;
  EXPECT_EQ(one.stats.rays, two.stats.rays);
  EXPECT_EQ(one.stats.samples, uint64_t(37 * 21 * 4));
  // A different seed gives a different image (the seed reaches the pixel streams).
  options.seed = 12;
  const RenderResult other = render(scene, path, options);
  size_t differing = 0;
  for (size_t i = 0; i < one.image.pixels.size(); ++i)
    differing += (one.image.pixels[i] != other.image.pixels[i]).any();
  EXPECT_GT(differing, one.image.pixels.size() / 2);
  // Adaptive batches that are not multiples of a packet (20, then 7 at a time).
  AdaptiveSampling sampling;
  sampling.minSamples = 20;
  sampling.batch = 7;
  sampling.maxSamples = 41;
  sampling.threshold = 0.02;
  const AdaptiveIntegrator adaptive(std::make_shared<PathIntegrator>(PathIntegrator::Params{}),
                                    sampling);
  options.seed = 11;
  options.threads = 1;
  const RenderResult adaptiveOne = render(scene, adaptive, options);
  options.threads = 2;
  const RenderResult adaptiveTwo = render(scene, adaptive, options);
  for (size_t i = 0; i < adaptiveOne.image.pixels.size(); ++i) {
    ASSERT_TRUE((adaptiveOne.image.pixels[i] == adaptiveTwo.image.pixels[i]).all()) << i;
    ASSERT_EQ(adaptiveOne.pixelSamples[i], adaptiveTwo.pixelSamples[i]) << "pixel " << i;
  }
  // Both stopping points were reached: 20 + 7k samples, some pixels stopping early.
  EXPECT_EQ(adaptiveOne.stats.minPixelSamples, 20u);
  EXPECT_EQ(adaptiveOne.stats.maxPixelSamples, 41u);
}

TEST(Renderer, SamplesDoNotDependOnHowCameraRaysArePacked) {
  // A pixel's camera rays are traced in packets of up to 16, the batch's first. A sample must
  // get the same camera ray and the same path numbers however its batch is cut: 16 samples as
  // one packet (plain 16 spp) and as packets of 3, 5, 5 and 3 (adaptive batches that never
  // stop early but at a constant pixel) must give the same pixels to the bit. This fails if a
  // camera offset is drawn from the path's stream, or if a lane of a short packet is dropped.
  RenderScene scene;
  sphereOnFloorScene(scene, 23, 17);
  RenderOptions options;
  options.samplesPerPixel = 16;
  options.seed = 5;
  options.threads = 2;
  const RenderResult plain = render(scene, PathIntegrator({}), options);
  AdaptiveSampling sampling;
  sampling.minSamples = 3;
  sampling.batch = 5;
  sampling.maxSamples = 16;
  sampling.threshold = 1e-300;  // stops only where every sample is the same (variance 0)
  const AdaptiveIntegrator cut(std::make_shared<PathIntegrator>(PathIntegrator::Params{}),
                               sampling);
  const RenderResult packed = render(scene, cut, options);
  size_t full = 0;
  for (size_t i = 0; i < plain.image.pixels.size(); ++i) {
    if (packed.pixelSamples[i] != 16) continue;
    ++full;
    ASSERT_TRUE((plain.image.pixels[i] == packed.image.pixels[i]).all()) << "pixel " << i;
  }
  // Most pixels see the sphere or the floor, whose samples vary: they all took 16.
  EXPECT_GT(full, plain.image.pixels.size() / 2);
}

TEST(Renderer, LeavesTheCallersFloatingPointModeAsItWas) {
  // The tiles are traced with flush-to-zero and denormals-are-zero set, as Embree asks, and TBB
  // runs some on the calling thread: that thread's mode must come back as it was, or a
  // caller's later arithmetic on tiny numbers would silently give zero.
  RenderScene scene;
  furnaceScene(scene, 16, 16);
  const unsigned before = _mm_getcsr();
  _mm_setcsr(before & ~unsigned(_MM_FLUSH_ZERO_ON | 0x0040));  // both off (0x0040: DAZ)
  const unsigned kFlags = 0x3f;  // the sticky exception flags, which arithmetic sets
  const unsigned mode = _mm_getcsr() & ~kFlags;
  for (const int threads : {1, 2}) {
    RenderOptions options;
    options.samplesPerPixel = 2;
    options.threads = threads;
    (void)render(scene, PathIntegrator({}), options);
    EXPECT_EQ(_mm_getcsr() & ~kFlags, mode) << threads << " threads";
    volatile double tiny = 1e-310;  // a denormal
    EXPECT_GT(tiny * 0.5, 0.0) << threads << " threads";
  }
  _mm_setcsr(before);
}

// An integrator that returns NaN or infinity for some samples.
class PoisonedIntegrator final : public Integrator {
 public:
  Color radianceFrom(const RenderScene&, const Ray&, const std::optional<SurfaceInteraction>&,
                     Pcg32& rng, uint64_t&) const override {
    const double u = rng.nextDouble();
    if (u < 0.1) return Color(std::nan(""), 1.0, 1.0);
    if (u < 0.2) return Color(kInfinity, 0.0, 0.0);
    return Color::Ones();
  }
  std::string toString() const override { return "poisoned"; }
};

TEST(Renderer, NonFiniteSamplesNeverReachTheFilm) {
  RenderScene scene;
  furnaceScene(scene, 8, 8);
  RenderOptions options;
  options.samplesPerPixel = 50;
  const RenderResult r = render(scene, PoisonedIntegrator(), options);
  for (const Color& c : r.image.pixels) {
    ASSERT_TRUE(c.allFinite());
    EXPECT_LE(c.maxCoeff(), 1.0);
  }
  // About 20% of 3200 samples were poisoned; each one is counted.
  EXPECT_GT(r.stats.nonFiniteSamples, 400u);
  EXPECT_LT(r.stats.nonFiniteSamples, 900u);
}

TEST(Renderer, AdaptiveSamplingStopsWhereThePixelIsKnown) {
  RenderScene scene;
  furnaceScene(scene, 16, 16);
  AdaptiveSampling sampling;
  sampling.minSamples = 8;
  sampling.maxSamples = 256;
  sampling.batch = 8;
  sampling.threshold = 0.05;
  const AdaptiveIntegrator adaptive(std::make_shared<PathIntegrator>(PathIntegrator::Params{}),
                                    sampling);
  RenderOptions options;
  const RenderResult r = render(scene, adaptive, options);
  // Background pixels see the constant environment exactly and stop at the minimum; sphere
  // pixels are noisy and take more, so the mean lies strictly between the bounds.
  EXPECT_GT(r.stats.meanSamplesPerPixel(), 8.0);
  EXPECT_LT(r.stats.meanSamplesPerPixel(), 256.0);
  EXPECT_EQ(r.stats.finishedPixels, 256u);
  EXPECT_FLOAT_EQ(float(r.image.at(0, 0)[0]), 0.5f);
  // The least and most samples a pixel got: the minimum (background) and more (the sphere).
  EXPECT_EQ(r.stats.minPixelSamples, 8u);
  EXPECT_GT(r.stats.maxPixelSamples, 8u);
  EXPECT_LE(r.stats.maxPixelSamples, 256u);
  EXPECT_FALSE(r.stats.stopped);
}

TEST(Renderer, CancelLeavesPixelsBlackAndCountsThem) {
  RenderScene scene;
  furnaceScene(scene, 16, 16);
  std::atomic<bool> cancel{true};
  RenderOptions options;
  options.cancel = &cancel;
  const RenderResult r = render(scene, PathIntegrator({}), options);
  EXPECT_EQ(r.stats.unfinishedPixels, 256u);
  EXPECT_EQ(r.stats.samples, 0u);
  EXPECT_TRUE(r.stats.stopped);
  EXPECT_EQ(r.stats.minPixelSamples, 0u);
  EXPECT_EQ(r.stats.maxPixelSamples, 0u);
  for (const Color& c : r.image.pixels) EXPECT_TRUE(isBlack(c));
  // Uncancelled, every pixel gets the fixed count.
  cancel = false;
  options.samplesPerPixel = 3;
  const RenderResult full = render(scene, PathIntegrator({}), options);
  EXPECT_FALSE(full.stats.stopped);
  EXPECT_EQ(full.stats.minPixelSamples, 3u);
  EXPECT_EQ(full.stats.maxPixelSamples, 3u);
}

// An integrator whose every sample takes at least a millisecond.
class SlowIntegrator final : public Integrator {
 public:
  Color radianceFrom(const RenderScene&, const Ray&, const std::optional<SurfaceInteraction>&,
                     Pcg32&, uint64_t&) const override {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    return Color::Ones();
  }
  std::string toString() const override { return "slow"; }
};

TEST(Renderer, FirstPixelTimeCountsRenderedPixelsOnly) {
  RenderScene scene;
  furnaceScene(scene, 8, 8);
  RenderOptions options;
  options.samplesPerPixel = 1;
  options.threads = 1;
  const SlowIntegrator slow;
  const RenderResult r = render(scene, slow, options);
  // One thread: the first pixel took a millisecond, and the 63 after it took one each.
  EXPECT_GE(r.stats.firstPixelSeconds, 0.001);
  EXPECT_GE(r.stats.seconds - r.stats.firstPixelSeconds, 0.063);
  // Resumed pixels are not rendered: with every pixel resumed there is no first pixel.
  RenderState state;
  state.width = 8;
  state.height = 8;
  state.samples.assign(64, 1);
  state.pixels.assign(64, Color::Ones());
  options.resume = &state;
  const RenderResult resumed = render(scene, slow, options);
  EXPECT_EQ(resumed.stats.resumedPixels, 64u);
  EXPECT_EQ(resumed.stats.firstPixelSeconds, 0.0);
  // All but the last: the first rendered pixel is the last one, after no resumed pixel's cost.
  state.samples.back() = 0;
  const RenderResult one = render(scene, slow, options);
  EXPECT_GE(one.stats.firstPixelSeconds, 0.001);
  EXPECT_LE(one.stats.firstPixelSeconds, one.stats.seconds);
}

TEST(Renderer, ImageBytesCountTheFilmAndItsOutputCopies) {
  // 24-byte double pixels, 12-byte float and 3-byte sRGB copies, 8 bytes of bookkeeping.
  EXPECT_EQ(renderImageBytes(32, 32), 32u * 32u * 47u);
  EXPECT_EQ(renderImageBytes(32768, 32768), uint64_t(32768) * 32768 * 47);
  EXPECT_EQ(renderImageBytes(-1, 5), 0u);
}

TEST(Renderer, RejectsBadOptions) {
  RenderScene scene;
  furnaceScene(scene, 4, 4);
  RenderOptions options;
  options.samplesPerPixel = 0;
  EXPECT_THROW(render(scene, PathIntegrator({}), options), Error);
  options.samplesPerPixel = 1;
  options.threads = -1;
  EXPECT_THROW(render(scene, PathIntegrator({}), options), Error);
}

}  // namespace
}  // namespace quadtri::testing
