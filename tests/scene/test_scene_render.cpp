// prepareSceneRender: what `quadtri render` and the Python module's render() share.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "quadtri/math/error.h"
#include "quadtri/scene/scene_render.h"

namespace quadtri {
namespace {

namespace fs = std::filesystem;

class SceneRenderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("quadtri_scene_render_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::create_directories(dir_);
    std::ofstream(dir_ / "tri.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    std::ofstream(dir_ / "scene.xml") << R"(<scene version="3.0.0">
  <default name="spp" value="3"/>
  <sensor type="perspective"><float name="fov" value="30"/>
    <transform name="to_world"><lookat origin="0, 0, 6" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="2"/></film>
    <sampler type="independent"><integer name="sample_count" value="$spp"/>
      <integer name="seed" value="5"/></sampler>
  </sensor>
  <shape type="obj"><string name="filename" value="tri.obj"/></shape>
  <emitter type="constant"><rgb name="radiance" value="1"/></emitter>
</scene>)";
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(SceneRenderTest, TakesTheFilesSettingsWithoutOverrides) {
  const PreparedRender p = prepareSceneRender(dir_ / "scene.xml", {});
  EXPECT_EQ(p.options.samplesPerPixel, 3);
  EXPECT_EQ(p.options.seed, 5u);
  EXPECT_EQ(p.built.inputTriangles, 1u);
  EXPECT_EQ(p.built.scene->camera().width(), 4);
}

TEST_F(SceneRenderTest, AppliesDefinesAndOverrides) {
  SceneRenderRequest request;
  // (Initialised whole: assigning a literal to a map entry trips GCC 12's -Wrestrict at -O3.)
  request.settings.defines = {{"spp", "7"}, {"unused", "1"}};
  request.settings.seed = 11;
  request.settings.threads = 2;
  request.settings.timeLimitSeconds = 4.5;
  request.settings.model = "flat";
  std::vector<std::string> warnings;
  request.warn = [&](const std::string& w) { warnings.push_back(w); };
  PreparedRender p = prepareSceneRender(dir_ / "scene.xml", request);
  EXPECT_EQ(p.options.samplesPerPixel, 7);
  EXPECT_EQ(p.options.seed, 11u);
  EXPECT_EQ(p.options.threads, 2);
  EXPECT_EQ(p.options.timeLimitSeconds, 4.5);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("-D unused=1: "), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("has no <default name=\"unused\">"), std::string::npos);

  request.settings.samplesPerPixel = 2;  // --spp wins over the define
  p = prepareSceneRender(dir_ / "scene.xml", request);
  EXPECT_EQ(p.options.samplesPerPixel, 2);
}

TEST_F(SceneRenderTest, RejectsBadRequestsAndNamesTheSceneLine) {
  auto messageOf = [&](const SceneRenderRequest& request) -> std::string {
    try {
      prepareSceneRender(dir_ / "scene.xml", request);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  SceneRenderRequest bad;
  bad.settings.samplesPerPixel = 0;
  EXPECT_EQ(messageOf(bad), "spp 0: expected a positive count");
  bad = {};
  bad.settings.threads = -1;
  EXPECT_EQ(messageOf(bad), "threads -1: expected 0 (all) or a positive count");
  bad = {};
  bad.settings.model = "nope";
  EXPECT_NE(messageOf(bad).find("nope"), std::string::npos);
  bad = {};
  bad.settings.defines = {{"spp", "x"}};
  EXPECT_NE(messageOf(bad).find("scene.xml:"), std::string::npos) << messageOf(bad);
}

}  // namespace
}  // namespace quadtri
