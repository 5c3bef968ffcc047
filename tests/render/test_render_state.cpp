// Checkpoints and resuming: a resumed render is the uninterrupted one, bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <mutex>

#include "quadtri/render/integrator/adaptive_integrator.h"
#include "quadtri/render/integrator/path_integrator.h"
#include "quadtri/render/render_state.h"
#include "render_fixtures.h"

namespace quadtri::testing {
namespace {

namespace fs = std::filesystem;

void sphereScene(RenderScene& scene, int width, int height) {
  scene.addSphere(Vec3::Zero(), 1.0, Mat4::Identity(), false, diffuse(0.6), std::nullopt, "sphere");
  // A wall of triangles behind it, so that camera rays go through Embree's packets.
  TriangleMesh wall;
  wall.positions = {Vec3(-3, -3, -1.5), Vec3(3, -3, -1.5), Vec3(3, 3, -1.5), Vec3(-3, 3, -1.5)};
  wall.triangles = {{0, 1, 2}, {0, 2, 3}};
  addMesh(scene, std::move(wall), "flat", diffuse(0.5));
  scene.setEnvironment(Color::Constant(0.8));
  scene.setCamera(makeCamera(Vec3(0, 0, 3.5), Vec3::Zero(), 45.0, width, height));
  scene.commit();
}

// A cancel flag that trips after `n` pixels have asked, so a render stops part way.
class CountingIntegrator final : public Integrator {
 public:
  CountingIntegrator(std::atomic<bool>& cancel, uint64_t stopAfterSamples)
      : cancel_(cancel), stopAfter_(stopAfterSamples) {}
  Color radianceFrom(const RenderScene& scene, const Ray& ray,
                     const std::optional<SurfaceInteraction>& first, Pcg32& rng,
                     uint64_t& rays) const override {
    if (++samples_ >= stopAfter_) cancel_.store(true);
    return path_.radianceFrom(scene, ray, first, rng, rays);
  }
  std::string toString() const override { return "counting"; }

 private:
  std::atomic<bool>& cancel_;
  uint64_t stopAfter_;
  mutable std::atomic<uint64_t> samples_{0};
  PathIntegrator path_{{}};
};

TEST(RenderState, ResumedRenderEqualsTheUninterruptedOneBitForBit) {
  RenderScene scene;
  sphereScene(scene, 40, 24);
  RenderOptions options;
  options.samplesPerPixel = 8;
  options.seed = 5;
  options.threads = 2;
  const RenderResult whole = render(scene, PathIntegrator({}), options);

  std::atomic<bool> cancel{false};
  RenderOptions first = options;
  first.cancel = &cancel;
  const RenderResult part = render(scene, CountingIntegrator(cancel, 8 * 300), first);
  ASSERT_GT(part.stats.unfinishedPixels, 0u);
  ASSERT_GT(part.stats.finishedPixels, 0u);
  const RenderState state = part.state(42);
  EXPECT_EQ(state.key, 42u);
  EXPECT_EQ(state.finishedPixels(), part.stats.finishedPixels);
  for (size_t i = 0; i < state.samples.size(); ++i)
    ASSERT_TRUE(state.samples[i] == 0 || state.samples[i] == 8) << i;

  // Through the file and back, then the rest on one thread.
  const fs::path file = fs::temp_directory_path() / "quadtri_test_render_state.state";
  saveRenderState(state, file);
  const RenderState loaded = loadRenderState(file);
  EXPECT_EQ(loaded.key, 42u);
  EXPECT_EQ(loaded.samples, state.samples);
  RenderOptions rest = options;
  rest.threads = 1;
  rest.resume = &loaded;
  const RenderResult resumed = render(scene, PathIntegrator({}), rest);
  EXPECT_EQ(resumed.stats.resumedPixels, part.stats.finishedPixels);
  EXPECT_EQ(resumed.stats.finishedPixels, 40u * 24u);
  EXPECT_EQ(resumed.stats.samples, whole.stats.samples);
  for (size_t i = 0; i < whole.image.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c)
      ASSERT_EQ(resumed.image.pixels[i][c], whole.image.pixels[i][c]) << "pixel " << i;
  fs::remove(file);
}

TEST(RenderState, CheckpointsHoldFinishedPixelsWithTheirFinalValues) {
  RenderScene scene;
  sphereScene(scene, 32, 32);
  RenderOptions options;
  options.samplesPerPixel = 64;
  options.threads = 2;
  options.stateKey = 7;
  // Far below the render's time (a 32² render at 64 samples ended before a 10 ms interval
  // on a fast run), so checkpoints are always taken.
  options.checkpointSeconds = 0.001;
  std::mutex mutex;
  std::vector<RenderState> states;
  options.checkpoint = [&](const RenderState& s) {
    std::lock_guard<std::mutex> lock(mutex);
    states.push_back(s);
  };
  const RenderResult r = render(scene, PathIntegrator({}), options);
  ASSERT_FALSE(states.empty());
  EXPECT_EQ(r.stats.checkpoints, states.size());
  EXPECT_TRUE(r.checkpointError.empty());
  size_t previous = 0;
  for (const RenderState& s : states) {
    EXPECT_EQ(s.key, 7u);
    EXPECT_GE(s.finishedPixels(), previous);  // pixels only ever finish
    previous = s.finishedPixels();
    for (size_t i = 0; i < s.samples.size(); ++i) {
      if (s.samples[i] == 0) {
        ASSERT_TRUE(isBlack(s.pixels[i]));
        continue;
      }
      ASSERT_EQ(s.samples[i], 64u);
      ASSERT_TRUE((s.pixels[i] == r.image.pixels[i]).all()) << "pixel " << i;
    }
  }
  // A callback that throws stops the checkpoints, not the render. The render lasts far longer
  // than the 1 ms between checkpoints (64² pixels at 256 samples), so one is always due.
  RenderScene longer;
  sphereScene(longer, 64, 64);
  options.samplesPerPixel = 256;
  options.checkpoint = [](const RenderState&) { fail("disk full"); };
  const RenderResult failing = render(longer, PathIntegrator({}), options);
  EXPECT_EQ(failing.checkpointError, "disk full");
  EXPECT_EQ(failing.stats.finishedPixels, 64u * 64u);
}

TEST(RenderState, MismatchedStatesAndFilesAreRefused) {
  RenderScene scene;
  sphereScene(scene, 8, 8);
  RenderOptions options;
  options.samplesPerPixel = 4;
  RenderState other;
  other.width = 8;
  other.height = 9;
  other.samples.assign(72, 0);
  other.pixels.assign(72, Color::Zero());
  options.resume = &other;
  EXPECT_THROW(render(scene, PathIntegrator({}), options), Error);
  other.height = 8;
  other.samples.assign(64, 0);
  other.pixels.assign(64, Color::Zero());
  other.samples[3] = 5;  // another samples-per-pixel count
  EXPECT_THROW(render(scene, PathIntegrator({}), options), Error);

  const fs::path file = fs::temp_directory_path() / "quadtri_test_bad.state";
  std::ofstream(file, std::ios::binary) << "QTRSTATE but too short";
  try {
    loadRenderState(file);
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
  }
  std::ofstream(file, std::ios::binary) << std::string(64, 'x');
  EXPECT_THROW(loadRenderState(file), Error);

  // A saved state whose pixel is NaN (found by fuzz_render_state): refused, naming the pixel.
  RenderState nan;
  nan.width = 2;
  nan.height = 1;
  nan.samples = {4, 4};
  nan.pixels = {Color(0.5, 0.5, 0.5), Color(0.5, std::nan(""), 0.5)};
  saveRenderState(nan, file);
  try {
    loadRenderState(file);
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("pixel 1 (x 1, y 0) has a non-finite value"),
              std::string::npos)
        << e.what();
  }
  fs::remove(file);
}

}  // namespace
}  // namespace quadtri::testing
