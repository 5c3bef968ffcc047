// `quadtri render --checkpoint` killed by SIGKILL between checkpoints and `--resume`d gives the
// uninterrupted render's pixels exactly; a state from another render is refused.
#include <gtest/gtest.h>

#include <fstream>

#include "cli/cli_runner.h"
#include "quadtri/io/image_module.h"

namespace quadtri::test {
namespace {

namespace fs = std::filesystem;

std::vector<float> readPixels(const fs::path& path) {
  ImageFileSpec spec;
  std::vector<float> rgb;
  if (!imageModule().read(path.string(), spec, rgb).empty() || spec.channels != 3) return {};
  return rgb;
}

TEST(RenderCheckpoint, KilledBetweenCheckpointsAndResumedEqualsTheUninterruptedRender) {
  const fs::path dir = freshDir("checkpoint");
  std::ofstream(dir / "scene.xml") << R"(<scene version="3.0.0">
  <default name="albedo" value="0.5"/>
  <integrator type="path"><integer name="max_depth" value="3"/></integrator>
  <sensor type="perspective">
    <float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="24"/><integer name="height" value="24"/></film>
    <sampler type="independent"><integer name="sample_count" value="4"/></sampler>
  </sensor>
  <emitter type="constant"><rgb name="radiance" value="1, 1, 1"/></emitter>
  <bsdf type="diffuse" id="grey"><rgb name="reflectance" value="$albedo, $albedo, $albedo"/></bsdf>
  <shape type="sphere"><ref id="grey"/></shape>
</scene>
)";
  const std::string scene = (dir / "scene.xml").string();
  const std::vector<std::string> common = {"render", scene, "--spp", "10000", "--seed", "7"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = common;
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  };
  CliProcess reference(with({"--threads", "2", "-o", (dir / "ref.exr").string()}), dir, "ref");
  ASSERT_EQ(reference.wait(), 0) << reference.stderrText();

  // Killed (SIGKILL: no handler runs) after its first checkpoint, before it finishes.
  const fs::path out = dir / "out.exr", state = dir / "out.exr.state";
  CliProcess killed(with({"--threads", "2", "--checkpoint", "0.3", "-o", out.string()}), dir,
                    "killed");
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!fs::exists(state) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ASSERT_TRUE(fs::exists(state)) << killed.stderrText();
  killed.signal(SIGKILL);
  killed.wait();
  EXPECT_TRUE(killed.killedBySignal());
  EXPECT_FALSE(fs::exists(out));

  // A state from another seed or scene is refused, and nothing is written.
  CliProcess seed({"render", scene, "--spp", "10000", "--seed", "8", "--resume", state.string(),
                   "-o", (dir / "other.exr").string()},
                  dir, "seed");
  EXPECT_EQ(seed.wait(), 1);
  EXPECT_NE(seed.stderrText().find("the render state was saved by another render"),
            std::string::npos)
      << seed.stderrText();
  CliProcess other(
      with({"-D", "albedo=0.6", "--resume", state.string(), "-o", (dir / "other.exr").string()}),
      dir, "other");
  EXPECT_EQ(other.wait(), 1);
  EXPECT_NE(other.stderrText().find(state.string() + ": the render state was saved by another"),
            std::string::npos)
      << other.stderrText();
  EXPECT_FALSE(fs::exists(dir / "other.exr"));

  // Resumed, on another thread count and without --checkpoint: the reference's pixels exactly.
  CliProcess resumed(with({"--threads", "1", "--resume", state.string(), "-o", out.string()}), dir,
                     "resumed");
  ASSERT_EQ(resumed.wait(), 0) << resumed.stderrText();
  const long already = numberBefore(resumed.stderrText(), " of 576 pixels already rendered");
  EXPECT_GT(already, 0) << resumed.stderrText();
  EXPECT_LT(already, 576);
  const std::vector<float> a = readPixels(dir / "ref.exr"), b = readPixels(out);
  ASSERT_EQ(a.size(), 24u * 24u * 3u);
  ASSERT_EQ(b.size(), a.size());
  for (size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a[i], b[i]) << "value " << i;
  // The image is complete: the state it resumed, its own, is gone (a later --resume would
  // otherwise render the missing pixels again).
  EXPECT_FALSE(fs::exists(state));
  fs::remove_all(dir);
}

TEST(RenderCheckpoint, StoppedRenderSavesItsStateAndSaysHowToResume) {
  const fs::path dir = freshDir("checkpoint-stop");
  std::ofstream(dir / "scene.xml") << R"(<scene version="3.0.0">
  <sensor type="perspective">
    <float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/></film>
  </sensor>
  <emitter type="constant"><rgb name="radiance" value="1, 1, 1"/></emitter>
  <shape type="sphere"/>
</scene>
)";
  const fs::path out = dir / "out.exr", state = dir / "out.exr.state";
  CliProcess p({"render", (dir / "scene.xml").string(), "--spp", "200000", "--threads", "2",
                "--checkpoint", "100", "-o", out.string()},
               dir);
  ASSERT_TRUE(p.waitForStderr("rendering 16x16")) << p.stderrText();
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  p.signal(SIGTERM);
  EXPECT_EQ(p.wait(), 128 + SIGTERM);
  EXPECT_NE(
      p.stderrText().find("saved " + state.string() + ", resume with --resume " + state.string()),
      std::string::npos)
      << p.stderrText();
  EXPECT_TRUE(fs::exists(state));
  EXPECT_TRUE(fs::exists(out));
  EXPECT_TRUE(temporaryFiles(dir).empty());
  fs::remove_all(dir);
}

}  // namespace
}  // namespace quadtri::test
