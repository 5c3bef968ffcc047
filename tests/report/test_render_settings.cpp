// One meaning for --spp, --seed, -D, --threads, --time (RenderSettings): `render` (through
// prepareSceneRender) and `figure` (renderFigureCells) render the same image from the same
// settings, and --spp caps an adaptive integrator in both.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "quadtri/math/error.h"
#include "quadtri/report/figure.h"
#include "quadtri/scene/render_settings.h"
#include "quadtri/scene/scene_render.h"

namespace quadtri::testing {
namespace {

namespace fs = std::filesystem;

/// An adaptive integrator that stops only at zero variance (threshold 1e-12), up to
/// max_samples 64, a 64-sample sampler, and a diffuse octahedron lit by the sky.
void writeAdaptiveScene(const fs::path& file, const fs::path& mesh) {
  std::ofstream(mesh) << "v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n"
                         "f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n";
  std::ofstream(file) << R"(<scene version="3.0.0">
  <default name="model" value="shading"/>
  <integrator type="adaptive"><float name="threshold" value="1e-12"/>
    <integer name="min_samples" value="16"/><integer name="max_samples" value="64"/>
  </integrator>
  <sensor type="perspective"><float name="fov" value="50"/>
    <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="6"/><integer name="height" value="5"/></film>
    <sampler type="independent"><integer name="sample_count" value="64"/></sampler>
  </sensor>
  <emitter type="constant"><rgb name="radiance" value="1"/></emitter>
  <shape type="obj"><string name="filename" value=")"
                      << mesh.filename().string() << R"("/>
    <string name="model" value="$model"/></shape>
</scene>)";
}

class RenderSettingsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("quadtri_settings_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    writeAdaptiveScene(dir_ / "t-octa.xml", dir_ / "octa.obj");
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(RenderSettingsTest, FigureAndRenderGiveSppTheSameMeaning) {
  RenderSettings settings;
  settings.samplesPerPixel = 4;
  settings.seed = 9;
  settings.threads = 2;

  SceneRenderRequest request;
  request.settings = settings;
  request.settings.model = "quadric-implicit-robust";
  PreparedRender prepared = prepareSceneRender(dir_ / "t-octa.xml", request);
  ASSERT_TRUE(prepared.built.integrator->adaptive());
  EXPECT_EQ(prepared.built.integrator->adaptive()->maxSamples, 4);  // --spp caps it
  const RenderResult rendered =
      render(*prepared.built.scene, *prepared.built.integrator, prepared.options);
  EXPECT_DOUBLE_EQ(rendered.stats.meanSamplesPerPixel(), 4.0);

  FigureRequest figure;
  figure.shapes = {"octa"};
  figure.models = {"quadric-implicit-robust"};
  figure.sceneFor = [&](const std::string& shape) { return dir_ / ("t-" + shape + ".xml"); };
  figure.settings = settings;
  const std::vector<FigureCell> cells = renderFigureCells(figure);
  ASSERT_EQ(cells.size(), 1u);
  // Before the settings were shared, figure --spp left the adaptive cap at max_samples (64).
  EXPECT_DOUBLE_EQ(cells[0].meanSamplesPerPixel, 4.0);
  ASSERT_EQ(cells[0].image.pixels.size(), rendered.image.pixels.size());
  for (size_t i = 0; i < rendered.image.pixels.size(); ++i)
    EXPECT_TRUE((cells[0].image.pixels[i] == rendered.image.pixels[i]).all()) << "pixel " << i;

  // Without --spp the scene's cap holds: pixels on the mesh take 64 samples, those of the sky
  // (zero variance) stop at min_samples 16.
  figure.settings.samplesPerPixel.reset();
  const double mean = renderFigureCells(figure)[0].meanSamplesPerPixel;
  EXPECT_GT(mean, 16.0);
  EXPECT_LE(mean, 64.0);
  // A model for every cell contradicts the columns.
  figure.settings.model = "flat";
  EXPECT_THROW(renderFigureCells(figure), Error);
}

TEST(RenderSettings, ValidationNamesTheOption) {
  auto messageOf = [](const RenderSettings& s, std::string_view prefix) -> std::string {
    try {
      s.validate(prefix);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  RenderSettings s;
  EXPECT_EQ(messageOf(s, "--"), "");
  s.samplesPerPixel = 0;
  EXPECT_EQ(messageOf(s, "--"), "--spp 0: expected a positive count");
  EXPECT_EQ(messageOf(s, ""), "spp 0: expected a positive count");
  s = {};
  s.threads = -2;
  EXPECT_EQ(messageOf(s, "--"), "--threads -2: expected 0 (all) or a positive count");
  s = {};
  s.timeLimitSeconds = -1;
  EXPECT_EQ(messageOf(s, ""), "time -1: expected a positive number of seconds");
  s = {};
  s.model = "nope";
  EXPECT_EQ(messageOf(s, "--").rfind("--model nope: unknown model; expected one of flat, ", 0), 0u)
      << messageOf(s, "--");
}

TEST(RenderSettings, DefinesListsAndApplying) {
  SceneDefines defines;
  addDefine(defines, "res=32");
  addDefine(defines, "name=a=b");  // the first '=' splits
  EXPECT_EQ(defines.at("res"), "32");
  EXPECT_EQ(defines.at("name"), "a=b");
  EXPECT_THROW(addDefine(defines, "=3"), Error);
  try {
    addDefine(defines, "res");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "-D res: expected name=value");
  }
  EXPECT_EQ(splitList("a,,b,"), (std::vector<std::string>{"a", "b"}));
  EXPECT_TRUE(splitList("").empty());

  RenderSettings s;
  s.samplesPerPixel = 3;
  s.seed = 42;
  s.threads = 5;
  s.timeLimitSeconds = 1.5;
  RenderOptions options;
  options.samplesPerPixel = 99;
  options.seed = 1;
  s.applyTo(options);
  EXPECT_EQ(options.samplesPerPixel, 3);
  EXPECT_EQ(options.seed, 42u);
  EXPECT_EQ(options.threads, 5);
  EXPECT_DOUBLE_EQ(options.timeLimitSeconds, 1.5);
  RenderSettings none;
  none.applyTo(options);  // seed and spp stay as the scene asked
  EXPECT_EQ(options.samplesPerPixel, 3);
  EXPECT_EQ(options.seed, 42u);
}

}  // namespace
}  // namespace quadtri::testing
