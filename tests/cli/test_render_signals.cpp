// `quadtri render` under a scheduler: SIGTERM and SIGHUP stop it as SIGINT does (the pixels so
// far are written, atomically, with a non-zero status and the samples per pixel on stderr); a
// second signal ends it at once and leaves no temporary file.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include "cli/cli_runner.h"
#include "quadtri/io/image_module.h"

namespace quadtri::test {
namespace {

namespace fs = std::filesystem;

// A grey sphere under a white sky: every rendered pixel is brighter than black, so the pixels
// the image got can be counted in the file. High spp so the render outlasts the test's signal.
void writeScene(const fs::path& path) {
  std::ofstream(path) << R"(<scene version="3.0.0">
  <default name="res" value="32"/>
  <integrator type="path"><integer name="max_depth" value="3"/></integrator>
  <sensor type="perspective">
    <float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="$res"/><integer name="height" value="$res"/></film>
    <sampler type="independent"><integer name="sample_count" value="4"/></sampler>
  </sensor>
  <emitter type="constant"><rgb name="radiance" value="1, 1, 1"/></emitter>
  <bsdf type="diffuse" id="grey"><rgb name="reflectance" value="0.5, 0.5, 0.5"/></bsdf>
  <shape type="sphere"><ref id="grey"/></shape>
</scene>
)";
}

struct ExrImage {
  int width = 0, height = 0;
  std::vector<float> rgb;
};

std::optional<ExrImage> readExr(const fs::path& path) {
  ImageFileSpec spec;
  ExrImage image;
  if (!imageModule().read(path.string(), spec, image.rgb).empty() || spec.channels != 3)
    return std::nullopt;
  image.width = spec.width;
  image.height = spec.height;
  return image;
}

// Starts a render that would take minutes, waits until it renders, then sends `signal`.
void stopWith(int signal, const std::string& name) {
  const fs::path dir = freshDir("signal-" + name);
  writeScene(dir / "scene.xml");
  const int spp = 200000;
  CliProcess p({"render", (dir / "scene.xml").string(), "--spp", std::to_string(spp), "--threads",
                "2", "-o", (dir / "out.exr").string(), "-o", (dir / "out.png").string()},
               dir);
  ASSERT_TRUE(p.waitForStderr("rendering 32x32")) << p.stderrText();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  p.signal(signal);
  const int status = p.wait();
  const std::string err = p.stderrText();
  EXPECT_EQ(status, 128 + signal) << err;
  EXPECT_FALSE(p.killedBySignal());
  // "quadtri: stopped by SIGTERM: 12 of 1024 pixels got 200000 samples each, the other 1012
  // got none (black); wrote .../out.exr, .../out.png"
  const size_t at = err.find("quadtri: stopped by " + name + ": ");
  ASSERT_NE(at, std::string::npos) << err;
  const std::string message = err.substr(at);
  const long finished = numberBefore(message, " of 1024 pixels got ");
  ASSERT_GE(finished, 0) << message;
  EXPECT_EQ(numberBefore(message, " samples each, the other "), spp) << message;
  EXPECT_EQ(finished + numberBefore(message, " got none (black); wrote "), 1024) << message;
  EXPECT_LT(finished, 1024);
  // The EXR is complete and holds exactly the finished pixels (the sky makes each non-black).
  const std::optional<ExrImage> image = readExr(dir / "out.exr");
  ASSERT_TRUE(image);
  EXPECT_EQ(image->width, 32);
  EXPECT_EQ(image->height, 32);
  int lit = 0;
  for (size_t i = 0; i < image->rgb.size(); i += 3) lit += image->rgb[i + 1] > 0.0f ? 1 : 0;
  EXPECT_EQ(lit, finished);
  EXPECT_TRUE(fs::exists(dir / "out.png"));
  EXPECT_TRUE(temporaryFiles(dir).empty());
  fs::remove_all(dir);
}

TEST(RenderSignals, SigtermWritesThePixelsSoFar) {
  stopWith(SIGTERM, "SIGTERM");
}

TEST(RenderSignals, SighupWritesThePixelsSoFar) {
  stopWith(SIGHUP, "SIGHUP");
}

TEST(RenderSignals, SigintWritesThePixelsSoFar) {
  stopWith(SIGINT, "SIGINT");
}

TEST(RenderSignals, SecondSignalExitsAtOnceWithoutTemporaryFiles) {
  const fs::path dir = freshDir("signal-twice");
  writeScene(dir / "scene.xml");
  // The second signal ends the process with its render threads still running, by design; under
  // ThreadSanitizer (make tsan) that is not reported as a thread leak.
  const char* tsan = std::getenv("TSAN_OPTIONS");
  const std::string tsanBefore = tsan ? tsan : "";
  ::setenv("TSAN_OPTIONS", (tsanBefore + " report_thread_leaks=0").c_str(), 1);
  // 2,000,000 samples per pixel: the pixels in flight take about a second to finish.
  CliProcess p({"render", (dir / "scene.xml").string(), "--spp", "2000000", "--threads", "2", "-o",
                (dir / "out.exr").string()},
               dir);
  ASSERT_TRUE(p.waitForStderr("rendering 32x32")) << p.stderrText();
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  p.signal(SIGTERM);
  // The second one later than at once: a signal sent while the same one is pending is merged
  // with it, and under load the process may not run for a while. So it is sent again every
  // 20 ms until the process says it stopped; the pixels in flight take far longer to finish.
  for (int again = 0; again < 250; ++again) {
    if (p.waitForStderr("again: stopped at once", 0.02) || p.finished()) break;
    p.signal(SIGTERM);
  }
  EXPECT_EQ(p.wait(), 128 + SIGTERM);
  if (tsan)
    ::setenv("TSAN_OPTIONS", tsanBefore.c_str(), 1);
  else
    ::unsetenv("TSAN_OPTIONS");
  EXPECT_NE(p.stderrText().find("SIGTERM again: stopped at once"), std::string::npos)
      << p.stderrText();
  EXPECT_TRUE(temporaryFiles(dir).empty());
  fs::remove_all(dir);
}

TEST(RenderSignals, SecondSignalWhileWritingRemovesTheTemporaryFile) {
  // A large image takes a while to encode: the second signal comes while its temporary file
  // exists, and the process must remove it before it exits.
  const fs::path dir = freshDir("signal-writing");
  writeScene(dir / "scene.xml");
  bool caught = false;
  for (int attempt = 0; attempt < 5 && !caught; ++attempt) {
    CliProcess p({"render", (dir / "scene.xml").string(), "-D", "res=2000", "--spp", "1",
                  "--threads", "2", "-o", (dir / "out.png").string()},
                 dir);
    ASSERT_TRUE(p.waitForStderr("rendering 2000x2000")) << p.stderrText();
    p.signal(SIGTERM);  // stops the render; what it has is written next
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (temporaryFiles(dir).empty() && !fs::exists(dir / "out.png") &&
           std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    caught = !temporaryFiles(dir).empty();
    if (caught) p.signal(SIGHUP);
    const int status = p.wait();
    EXPECT_TRUE(temporaryFiles(dir).empty());
    // SIGHUP ends it at once unless the file was renamed into place in the meantime.
    if (caught && status == 128 + SIGHUP) {
      EXPECT_NE(p.stderrText().find("SIGHUP again: stopped at once"), std::string::npos);
    } else {
      EXPECT_EQ(status, 128 + SIGTERM) << p.stderrText();
    }
    fs::remove(dir / "out.png");
  }
  EXPECT_TRUE(caught) << "the temporary file was never seen in 5 attempts";
  fs::remove_all(dir);
}

TEST(RenderSignals, ConvertStoppedWhileWritingLeavesNoTemporaryFile) {
  // Commands other than render have nothing to finish: a signal ends them at once, after
  // removing the temporary file of the output being written.
  const fs::path dir = freshDir("signal-convert");
  bool caught = false;
  for (int attempt = 0; attempt < 5 && !caught; ++attempt) {
    CliProcess p(
        {"convert", "icosphere:5", "--model", "quadric-param", "-o", (dir / "out.obj").string()},
        dir);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (temporaryFiles(dir).empty() && !fs::exists(dir / "out.obj") &&
           std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    caught = !temporaryFiles(dir).empty();
    if (caught) p.signal(SIGTERM);
    const int status = p.wait();
    EXPECT_TRUE(temporaryFiles(dir).empty());
    if (caught && status == 128 + SIGTERM) {
      EXPECT_NE(p.stderrText().find("quadtri: stopped by SIGTERM"), std::string::npos)
          << p.stderrText();
    } else {
      EXPECT_EQ(status, 0) << p.stderrText();  // renamed into place before the signal
    }
    fs::remove(dir / "out.obj");
  }
  EXPECT_TRUE(caught) << "the temporary file was never seen in 5 attempts";
  fs::remove_all(dir);
}

}  // namespace
}  // namespace quadtri::test
