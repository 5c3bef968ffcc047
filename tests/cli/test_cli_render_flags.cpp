// The rendering options (src/cli/render_flags.h) are parsed once: the same mistake gets the same
// message from `render`, `figure` and `study`, and `figure --spp` caps an adaptive integrator as
// `render --spp` does.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>

#include "cli/cli_runner.h"

namespace quadtri::test {
namespace {

namespace fs = std::filesystem;

const std::string kScenes = std::string(QUADTRI_TEST_DIR) + "/../scenes/thesis";

/// The first line of stderr after "quadtri: error: ".
std::string errorOf(const std::vector<std::string>& args, const fs::path& dir,
                    const std::string& tag) {
  CliProcess p(args, dir, tag);
  EXPECT_EQ(p.wait(), 1) << p.stderrText();
  const std::string err = p.stderrText();
  const std::string prefix = "quadtri: error: ";
  const size_t at = err.find(prefix);
  if (at == std::string::npos) return err;
  const size_t start = at + prefix.size();
  return err.substr(start, err.find('\n', start) - start);
}

TEST(CliRenderFlags, EveryCommandSaysTheSameAboutTheSameMistake) {
  const fs::path dir = freshDir("render-flags");
  const std::string scene = kScenes + "/a-triangle.xml";
  const std::string out = (dir / "x.exr").string(), png = (dir / "x.png").string();
  EXPECT_EQ(errorOf({"render", scene, "-o", out, "--spp", "0"}, dir, "r1"),
            "--spp 0: expected a positive count");
  EXPECT_EQ(errorOf({"figure", "--scenes", kScenes, "-o", png, "--spp", "0"}, dir, "f1"),
            "--spp 0: expected a positive count");
  EXPECT_EQ(errorOf({"render", scene, "-o", out, "-D", "res"}, dir, "r2"),
            "-D res: expected name=value");
  EXPECT_EQ(errorOf({"figure", "--scenes", kScenes, "-o", png, "-D", "res"}, dir, "f2"),
            "-D res: expected name=value");
  EXPECT_EQ(errorOf({"render", scene, "-o", out, "--threads", "-1"}, dir, "r3"),
            "--threads -1: expected 0 (all) or a positive count");
  EXPECT_EQ(
      errorOf({"study", dir.string(), "--out", (dir / "s").string(), "--threads", "-1"}, dir, "s3"),
      "--threads -1: expected 0 (all) or a positive count");
  const std::string unknownModel = "--model nope: unknown model; expected one of flat, ";
  EXPECT_EQ(
      errorOf({"render", scene, "-o", out, "--model", "nope"}, dir, "r4").rfind(unknownModel, 0),
      0u);
  EXPECT_EQ(errorOf({"study", dir.string(), "--out", (dir / "s").string(), "--model", "flat,nope"},
                    dir, "s4")
                .rfind(unknownModel, 0),
            0u);
  EXPECT_EQ(errorOf({"figure", "--scenes", kScenes, "-o", png, "--time", "0"}, dir, "f5"),
            "--time 0: expected a positive number of seconds");
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(png));
  fs::remove_all(dir);
}

TEST(CliRenderFlags, MistakesAreRefusedBeforeAnyWorkInOneVoice) {
  const fs::path dir = freshDir("render-mistakes");
  const std::string scene = kScenes + "/a-triangle.xml";
  const std::string out = (dir / "x.exr").string();
  // A sign on an unsigned option: CLI11 alone read "-5" as 2^64 - 5 (--lines ran for minutes,
  // --seed -1 rendered with seed 18446744073709551615).
  // (Each command fails fast if the check itself is lost: a mesh that does not exist, a tiny
  // render, not 2^64 lines or a long render.)
  const std::string missing = (dir / "missing.obj").string();
  EXPECT_EQ(errorOf({"analyze", missing, "--lines", "-5"}, dir, "a1"),
            "--lines: expected a whole number, 1 or more, got -5");
  // A mesh beyond what Embree traces: the crack rate's refusal names the file and the model.
  {
    const fs::path huge = dir / "huge.obj";
    std::ofstream(huge) << "v 0 0 0\nv 1e200 0 0\nv 0 1e200 0\nv 0 0 1e200\n"
                           "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n";
    const std::string message = errorOf({"analyze", huge.string(), "--model", "flat"}, dir, "a3");
    EXPECT_EQ(message.rfind(huge.string() + ": crack rate of flat: ", 0), 0u) << message;
    EXPECT_NE(message.find("vertex 1 has a coordinate of 1e+200"), std::string::npos) << message;
  }
  // A count that must be positive says so for a sign and for 0 alike.
  EXPECT_EQ(errorOf({"analyze", missing, "--lines", "0"}, dir, "a2"),
            "--lines: expected a whole number, 1 or more, got 0");
  EXPECT_EQ(errorOf({"study", "--lines", "00", "-o", (dir / "s").string(), missing}, dir, "s1"),
            "--lines: expected a whole number, 1 or more, got 00");
  EXPECT_EQ(
      errorOf({"render", scene, "-o", out, "-D", "res=8", "--spp", "1", "--seed", "-1"}, dir, "r1"),
      "--seed: expected a whole number, 0 or more, got -1");
  EXPECT_FALSE(fs::exists(out));
  // An output in a folder that does not exist is refused when parsed, not after the render.
  const std::string lost = (dir / "nodir" / "x.exr").string();
  // (A tiny render: were the check lost, it would fail at the write with other words.)
  EXPECT_EQ(errorOf({"render", scene, "-o", lost, "-D", "res=8", "--spp", "1"}, dir, "r2"),
            "--output: " + lost + ": the folder " + (dir / "nodir").string() + " does not exist");
  // figure's outputs may lie in a folder that its --cells makes; otherwise the same refusal,
  // before any render.
  EXPECT_EQ(errorOf({"figure", "--scenes", kScenes, "--shapes", "triangle", "--models", "flat",
                     "--res", "8", "--spp", "1", "-o", (dir / "nodir" / "f.png").string()},
                    dir, "f1"),
            "-o " + (dir / "nodir" / "f.png").string() + ": the folder " +
                (dir / "nodir").string() + " does not exist");
  {
    CliProcess made({"figure", "--scenes", kScenes, "--shapes", "triangle", "--models", "flat",
                     "--res", "8", "--spp", "1", "--cells", (dir / "new" / "cells").string(), "-o",
                     (dir / "new" / "f.png").string()},
                    dir, "f2");
    EXPECT_EQ(made.wait(), 0) << made.stderrText();
    EXPECT_TRUE(fs::exists(dir / "new" / "f.png"));
  }
  EXPECT_EQ(errorOf({"convergence", "--shapes", "icosphere", "--csv", lost}, dir, "c1"),
            "--csv: " + lost + ": the folder " + (dir / "nodir").string() + " does not exist");
  // The parser's own complaints read as every other error does, with exit status 1.
  EXPECT_EQ(errorOf({"mesh", "icosphere:3", "-o", (dir / "m.obj").string()}, dir, "m1")
                .rfind("name: icosphere:3 not in {", 0),
            0u);
  EXPECT_EQ(errorOf({"frobnicate"}, dir, "x1"), "A subcommand is required");
  fs::remove_all(dir);
}

TEST(CliRenderFlags, SceneErrorsNameTheElementNotItsParameters) {
  // A mesh the loader refuses, inside a scene: the message is the scene's line, the element's
  // tag and the loader's words, without the element's resolved parameters (its matrices, paths
  // and defaults ran to several lines before).
  const fs::path dir = freshDir("scene-errors");
  {
    std::ofstream obj(dir / "bad.obj");
    obj << "v 0 0 0\nv 1 0 0\nf 1 2 3\n";
    std::ofstream xml(dir / "scene.xml");
    xml << "<scene version=\"3.0.0\">\n"
           "  <sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/>\n"
           "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"8\"/>"
           "<integer name=\"height\" value=\"8\"/></film></sensor>\n"
           "  <shape type=\"obj\"><string name=\"filename\" value=\"bad.obj\"/></shape>\n"
           "</scene>\n";
  }
  const std::string message =
      errorOf({"render", (dir / "scene.xml").string(), "-o", (dir / "x.exr").string()}, dir, "s1");
  EXPECT_EQ(message.rfind((dir / "scene.xml").string() + ":4: <shape type=\"obj\">: " +
                              (dir / "bad.obj").string() + ":3: face vertex '3'",
                          0),
            0u)
      << message;
  EXPECT_EQ(message.find("to_world"), std::string::npos) << message;
  fs::remove_all(dir);
}

TEST(CliRenderFlags, FigureSppCapsTheAdaptiveIntegratorAsRenderDoes) {
  // Setup b's scenes are adaptive with min_samples 16; --spp 4 lowers it and caps each pixel at
  // 4, in figure as in render (figure used to leave the cap at $spp and refuse).
  const fs::path dir = freshDir("render-flags-spp");
  CliProcess render({"render", kScenes + "/b-triangle.xml", "-D", "res=8", "--spp", "4", "-o",
                     (dir / "r.exr").string()},
                    dir, "render");
  ASSERT_EQ(render.wait(), 0) << render.stderrText();
  EXPECT_NE(render.stdoutText().find("image           8x8, 4.0 samples/pixel"), std::string::npos)
      << render.stdoutText();
  CliProcess figure(
      {"figure", "--scenes", kScenes, "--setup", "b", "--shapes", "triangle", "--models", "shading",
       "--res", "8", "--spp", "4", "-o", (dir / "f.png").string()},
      dir, "figure");
  ASSERT_EQ(figure.wait(), 0) << figure.stderrText();
  EXPECT_NE(figure.stdoutText().find("4.0 spp"), std::string::npos) << figure.stdoutText();
  fs::remove_all(dir);
}

// `render` runs the fold and fallback check of a model with patches (implicit, Bézier or
// tessellated) after the image (it does not need it, and on a million triangles it took 0.1 to
// 0.5 s before the first pixel): the warning still comes, once, after "rendering ...", and the
// image is written.
TEST(CliRenderFlags, RenderWarnsOfAFoldingModelAfterTheImage) {
  const fs::path dir = freshDir("render-fold-warning");
  // Two triangles facing +z with equal normals, one corner lifted: no edge curve of the
  // quadric models can be tangent at both ends, so quadric-implicit and quadric-param (traced
  // as its tessellation) fall back on both.
  std::ofstream(dir / "step.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0.3\nv 0 1 0\nvn 0 0 1\n"
                                     "f 1//1 2//1 3//1\nf 1//1 3//1 4//1\n";
  for (const std::string model : {"quadric-implicit", "quadric-param"}) {
    SCOPED_TRACE(model);
    std::ofstream(dir / "s.xml") << R"(<scene version="3.0.0">
  <sensor type="perspective"><float name="fov" value="30"/>
    <transform name="to_world"><lookat origin="0.5, 0.5, 6" target="0.5, 0.5, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="4"/></film>
    <sampler type="independent"><integer name="sample_count" value="2"/></sampler>
  </sensor>
  <emitter type="constant"/>
  <shape type="obj"><string name="filename" value="step.obj"/><string name="model" value=")"
                                 << model << R"("/></shape>
</scene>)";
    fs::remove(dir / "r.exr");
    CliProcess render({"render", (dir / "s.xml").string(), "-o", (dir / "r.exr").string()}, dir,
                      "render");
    ASSERT_EQ(render.wait(), 0) << render.stderrText();
    const std::string err = render.stderrText();
    const std::string warning = "step.obj: " + model + " folds at ";
    const size_t at = err.find(warning);
    ASSERT_NE(at, std::string::npos) << err;
    EXPECT_EQ(err.find(warning, at + 1), std::string::npos) << err;
    EXPECT_NE(err.find("and falls back on 100% of patches (2 of 2)"), std::string::npos) << err;
    const size_t rendering = err.find("rendering 4x4");
    ASSERT_NE(rendering, std::string::npos) << err;
    EXPECT_LT(rendering, at) << err;
    EXPECT_TRUE(fs::exists(dir / "r.exr"));
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace quadtri::test
