// `quadtri render --tile I/N` and `--crop`, and `quadtri merge`: merged tiles are bitwise the
// one-shot render; tiles that miss, double or come from another render are refused, naming
// the tile files, and nothing is written.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>

#include "cli/cli_runner.h"
#include "quadtri/io/image_module.h"
#include "quadtri/math/error.h"
#include "quadtri/render/tiles.h"

namespace quadtri::test {
namespace {

namespace fs = std::filesystem;

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

struct Read {
  ImageFileSpec spec;
  std::vector<float> rgb;
  // The header's string attribute `name`, or `otherwise`.
  std::string attribute(const std::string& name, const std::string& otherwise = "") const {
    for (const auto& [key, value] : spec.attributes)
      if (key == name) return value;
    return otherwise;
  }
};

Read readExr(const fs::path& path) {
  Read r;
  if (!imageModule().read(path.string(), r.spec, r.rgb).empty() || r.spec.channels != 3)
    r.rgb.clear();
  return r;
}

// A 24x18 film: a diffuse sphere before a wall (triangles, so camera rays are traced in
// packets) under a constant emitter, 3 samples per pixel.
fs::path writeScene(const fs::path& dir) {
  std::ofstream(dir / "scene.xml") << R"(<scene version="3.0.0">
  <integrator type="path"><integer name="max_depth" value="3"/></integrator>
  <sensor type="perspective">
    <float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="24"/><integer name="height" value="18"/></film>
    <sampler type="independent"><integer name="sample_count" value="3"/></sampler>
  </sensor>
  <emitter type="constant"><rgb name="radiance" value="1, 1, 1"/></emitter>
  <shape type="sphere"><bsdf type="diffuse"/></shape>
  <shape type="rectangle">
    <transform name="to_world"><scale value="3, 3, 1"/><translate value="0, 0, -1.5"/></transform>
    <bsdf type="diffuse"/>
  </shape>
</scene>
)";
  return dir / "scene.xml";
}

int run(const std::vector<std::string>& args, const fs::path& dir, const std::string& tag,
        std::string* err = nullptr) {
  CliProcess p(args, dir, tag);
  const int rc = p.wait();
  if (err) *err = p.stderrText();
  return rc;
}

TEST(RenderTiles, TilesAreRowBandsThatCoverTheFilmOnce) {
  for (const int n : {1, 2, 3, 4, 7, 18}) {
    int next = 0;
    for (int i = 1; i <= n; ++i) {
      const PixelWindow w = tileWindow(TileIndex{i, n}, 24, 18);
      EXPECT_EQ(w.x, 0);
      EXPECT_EQ(w.width, 24);
      EXPECT_EQ(w.y, next);
      EXPECT_GE(w.height, 18 / n);
      EXPECT_LE(w.height, 18 / n + 1);
      next = w.y + w.height;
    }
    EXPECT_EQ(next, 18);
  }
  EXPECT_THROW(tileWindow(TileIndex{1, 19}, 24, 18), Error);
  EXPECT_THROW(TileIndex::parse("0/4"), Error);
  EXPECT_THROW(TileIndex::parse("5/4"), Error);
  EXPECT_THROW(PixelWindow::parse("1,2,3"), Error);
  EXPECT_EQ(PixelWindow::parse("1,2,3,4"), (PixelWindow{1, 2, 3, 4}));
}

TEST(RenderTiles, MergedTilesAreBitwiseTheOneShotRender) {
  const fs::path dir = freshDir("tiles");
  const std::string scene = writeScene(dir).string();
  ASSERT_EQ(run({"render", scene, "--seed", "5", "-o", (dir / "full.exr").string()}, dir, "full"),
            0);
  std::vector<std::string> merge = {"merge"};
  for (int i = 1; i <= 3; ++i) {
    const fs::path tile = dir / fmt::format("tile{}.exr", i);
    ASSERT_EQ(
        run({"render", scene, "--seed", "5", "--tile", fmt::format("{}/3", i), "-o", tile.string()},
            dir, "tile"),
        0);
    merge.push_back(tile.string());
  }
  // The tile keeps its place on the film: data window rows 6..11, display window the film.
  const Read second = readExr(dir / "tile2.exr");
  EXPECT_EQ(second.spec.x, 0);
  EXPECT_EQ(second.spec.y, 6);
  EXPECT_EQ(second.spec.width, 24);
  EXPECT_EQ(second.spec.height, 6);
  EXPECT_EQ(second.spec.fullWidth, 24);
  EXPECT_EQ(second.spec.fullHeight, 18);
  EXPECT_EQ(second.attribute("quadtri_tile"), "2/3");
  EXPECT_EQ(second.attribute("quadtri_seed"), "5");
  EXPECT_EQ(second.attribute("quadtri_spp"), "3");

  merge.insert(merge.end(), {"-o", (dir / "merged.exr").string()});
  std::string err;
  ASSERT_EQ(run(merge, dir, "merge", &err), 0) << err;
  const Read full = readExr(dir / "full.exr"), merged = readExr(dir / "merged.exr");
  ASSERT_EQ(full.rgb.size(), size_t(24 * 18 * 3));
  EXPECT_EQ(merged.spec.width, 24);
  EXPECT_EQ(merged.spec.height, 18);
  EXPECT_EQ(merged.rgb, full.rgb);  // bitwise: the same floats
  EXPECT_EQ(merged.attribute("quadtri_scene_key"), full.attribute("quadtri_scene_key"));

  // Crop windows of any shape merge the same way.
  const std::vector<std::string> crops = {"0,0,10,18", "10,0,14,5", "10,5,14,13"};
  merge = {"merge"};
  for (size_t i = 0; i < crops.size(); ++i) {
    const fs::path crop = dir / fmt::format("crop{}.exr", i);
    ASSERT_EQ(
        run({"render", scene, "--seed", "5", "--crop", crops[i], "-o", crop.string()}, dir, "crop"),
        0);
    merge.push_back(crop.string());
  }
  merge.insert(merge.end(), {"-o", (dir / "merged-crops.exr").string()});
  ASSERT_EQ(run(merge, dir, "merge-crops", &err), 0) << err;
  EXPECT_EQ(readExr(dir / "merged-crops.exr").rgb, full.rgb);
  fs::remove_all(dir);
}

TEST(RenderTiles, MergeRefusesMissingDoubledAndForeignTiles) {
  const fs::path dir = freshDir("tiles-errors");
  const std::string scene = writeScene(dir).string();
  const auto tile = [&](const std::string& name, std::vector<std::string> extra) {
    std::vector<std::string> args = {"render", scene, "-o", (dir / name).string()};
    args.insert(args.end(), extra.begin(), extra.end());
    if (std::find(extra.begin(), extra.end(), "--seed") == extra.end())
      args.insert(args.end(), {"--seed", "5"});
    std::string err;
    EXPECT_EQ(run(args, dir, "tile", &err), 0) << err;
    return (dir / name).string();
  };
  const std::string t1 = tile("t1.exr", {"--tile", "1/3"});
  const std::string t2 = tile("t2.exr", {"--tile", "2/3"});
  const std::string t3 = tile("t3.exr", {"--tile", "3/3"});
  const std::string overlap = tile("overlap.exr", {"--crop", "4,10,3,3"});
  const std::string seed8 = tile("seed8.exr", {"--tile", "3/3", "--seed", "8"});
  const std::string spp4 = tile("spp4.exr", {"--tile", "3/3", "--spp", "4"});
  const std::string out = (dir / "merged.exr").string();
  const auto mergeError = [&](std::vector<std::string> tiles) {
    std::vector<std::string> args = {"merge"};
    args.insert(args.end(), tiles.begin(), tiles.end());
    args.insert(args.end(), {"-o", out});
    std::string err;
    EXPECT_EQ(run(args, dir, "merge", &err), 1) << err;
    EXPECT_FALSE(fs::exists(out));
    EXPECT_TRUE(temporaryFiles(dir).empty());
    return err;
  };
  std::string err = mergeError({t1, t3});
  EXPECT_NE(err.find("no tile covers film window (--crop X,Y,W,H) 0,6,24,6: missing --tile 2/3"),
            std::string::npos)
      << err;
  err = mergeError({t1, t2, t3, overlap});
  EXPECT_NE(err.find(t2 + " and " + overlap + " both cover the 6 pixels of window 4,10,3,2"),
            std::string::npos)
      << err;
  EXPECT_NE(err.find(t3 + " and " + overlap + " both cover the 3 pixels of window 4,12,3,1"),
            std::string::npos)
      << err;
  err = mergeError({t1, t2, t3, t2});
  EXPECT_NE(err.find(t2 + ": given twice (tiles 2 and 4)"), std::string::npos) << err;
  // The output may not be one of the tiles: the merge would replace a tile it reads.
  {
    const std::string t2Bytes = readFile(t2);
    ASSERT_EQ(run({"merge", t1, t2, t3, "-o", t2}, dir, "merge-onto-tile", &err), 1) << err;
    EXPECT_NE(err.find(t2 + ": the output is also an input (tile 2)"), std::string::npos) << err;
    EXPECT_EQ(readFile(t2), t2Bytes);
  }
  err = mergeError({t1, t2, seed8});
  EXPECT_NE(err.find(seed8 + ": quadtri_seed 8, but " + t1 + " has 5"), std::string::npos) << err;
  err = mergeError({t1, t2, spp4});
  EXPECT_NE(err.find(spp4 + ": quadtri_spp 4, but " + t1 + " has 3"), std::string::npos) << err;

  // A tile cut short by --time (a microsecond: at most a few pixels start) is refused, named,
  // with its count of black pixels; --allow-unfinished merges it and says how many are black.
  const std::string cut = tile("cut.exr", {"--tile", "3/3", "--time", "0.000001"});
  const size_t unfinished = std::stoul(readExr(cut).attribute("quadtri_unfinished_pixels", "0"));
  EXPECT_GT(unfinished, 0u);
  EXPECT_LE(unfinished, 24u * 6u);
  EXPECT_EQ(readExr(t3).attribute("quadtri_unfinished_pixels"), "0");
  err = mergeError({t1, t2, cut});
  EXPECT_NE(err.find(fmt::format("{}: {} of its 144 pixels are not rendered", cut, unfinished)),
            std::string::npos)
      << err;
  EXPECT_NE(err.find("--allow-unfinished"), std::string::npos) << err;
  ASSERT_EQ(run({"merge", t1, t2, cut, "--allow-unfinished", "-o", out}, dir, "merge-cut", &err), 0)
      << err;
  EXPECT_NE(err.find(fmt::format("{} pixels of cut-short tiles are black", unfinished)),
            std::string::npos)
      << err;
  EXPECT_EQ(readExr(out).attribute("quadtri_unfinished_pixels"), std::to_string(unfinished));
  fs::remove(out);

  // A window cannot be a PNG: it could not say where it lies.
  ASSERT_EQ(
      run({"render", scene, "--tile", "1/3", "-o", (dir / "t.png").string()}, dir, "png", &err), 1);
  EXPECT_NE(err.find("written as .exr only"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir / "t.png"));
  fs::remove_all(dir);
}

// The recipe of the README: four tiles through GNU parallel, then merged.
TEST(RenderTiles, FourTilesThroughGnuParallelMergeToTheOneShotRender) {
  if (std::system("command -v parallel >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "GNU parallel is not on PATH (Debian package parallel)";
  const fs::path dir = freshDir("tiles-parallel");
  const std::string scene = writeScene(dir).string();
  ASSERT_EQ(run({"render", scene, "-o", (dir / "full.exr").string()}, dir, "full"), 0);
  const std::string command = fmt::format(
      "parallel --will-cite --halt now,fail=1 -j 4 '{}' render '{}' --threads 1 "
      "--tile {{}}/4 -o '{}/tile-{{}}.exr' ::: 1 2 3 4 >'{}/parallel.log' 2>&1",
      QUADTRI_CLI, scene, dir.string(), dir.string());
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  std::vector<std::string> merge = {"merge"};
  for (int i = 4; i >= 1; --i) merge.push_back((dir / fmt::format("tile-{}.exr", i)).string());
  merge.insert(merge.end(), {"-o", (dir / "merged.exr").string()});
  std::string err;
  ASSERT_EQ(run(merge, dir, "merge", &err), 0) << err;
  const Read full = readExr(dir / "full.exr");
  ASSERT_FALSE(full.rgb.empty());
  EXPECT_EQ(readExr(dir / "merged.exr").rgb, full.rgb);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace quadtri::test
