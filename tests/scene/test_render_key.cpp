// renderKey: what a render state is tied to.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "quadtri/math/error.h"
#include "quadtri/scene/render_key.h"
#include "quadtri/scene/scene_builder.h"
#include "quadtri/scene/scene_loader.h"
#include "quadtri/scene/shape/mesh_file_xml.h"

namespace quadtri {
namespace {

namespace fs = std::filesystem;

TEST(RenderKey, ChangesWithWhatTheImageDependsOnOnly) {
  const fs::path dir = fs::temp_directory_path() / "quadtri_test_render_key";
  fs::create_directories(dir);
  std::ofstream(dir / "tri.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  std::ofstream(dir / "scene.xml") << R"(<scene version="3.0.0">
  <default name="albedo" value="0.5"/>
  <sensor type="perspective">
    <float name="fov" value="40"/>
    <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
  </sensor>
  <bsdf type="diffuse" id="b"><rgb name="reflectance" value="$albedo, $albedo, $albedo"/></bsdf>
  <shape type="obj"><string name="filename" value="tri.obj"/><ref id="b"/></shape>
</scene>
)";
  const SceneDescription d = loadSceneDescription(dir / "scene.xml");
  RenderOptions options;
  options.samplesPerPixel = 16;
  options.seed = 3;
  const uint64_t key = renderKey(d, options, std::nullopt);
  EXPECT_EQ(renderKey(d, options, std::nullopt), key);
  RenderOptions same = options;
  same.threads = 7;
  same.timeLimitSeconds = 10;
  same.checkpointSeconds = 1;
  EXPECT_EQ(renderKey(d, same, std::nullopt), key);
  RenderOptions seed = options;
  seed.seed = 4;
  EXPECT_NE(renderKey(d, seed, std::nullopt), key);
  RenderOptions spp = options;
  spp.samplesPerPixel = 17;
  EXPECT_NE(renderKey(d, spp, std::nullopt), key);
  EXPECT_NE(renderKey(d, options, std::string("quadric-param")), key);
  EXPECT_NE(renderKey(loadSceneDescription(dir / "scene.xml", {{"albedo", "0.6"}}), options,
                      std::nullopt),
            key);
  // Command-line overrides that reach the description: the shapes' normals.
  SceneDescription averaged = d;
  overrideNormals(averaged, NormalSource::Average, std::nullopt);
  EXPECT_NE(renderKey(averaged, options, std::nullopt), key);
  SceneDescription creased = d;
  overrideNormals(creased, std::nullopt, 45.0);
  EXPECT_NE(renderKey(creased, options, std::nullopt), key);
  // The film's crop window and principal point, and the tent filter's radius.
  SceneDescription cropped = d;
  cropped.sensor.film.cropX = 1;
  EXPECT_NE(renderKey(cropped, options, std::nullopt), key);
  // Both keys from one pass: the render's, and the whole film's, which no crop window changes.
  const RenderKeys keys = renderKeys(d, options, std::nullopt);
  EXPECT_EQ(keys.render, key);
  EXPECT_EQ(keys.film, filmRenderKey(d, options, std::nullopt));
  EXPECT_EQ(keys.film, keys.render);  // without a crop window the render is the whole film
  cropped.sensor.film.cropWidth = 3;
  EXPECT_EQ(renderKeys(cropped, options, std::nullopt).film, keys.film);
  EXPECT_NE(renderKeys(cropped, options, std::nullopt).render, keys.render);
  SceneDescription whole = d;
  whole.sensor.film.cropWidth = whole.sensor.film.width;
  whole.sensor.film.cropHeight = whole.sensor.film.height;
  EXPECT_EQ(renderKey(whole, options, std::nullopt), keys.film);
  SceneDescription shifted = d;
  shifted.sensor.principalPointOffset = Vec2(0.1, 0.0);
  EXPECT_NE(renderKey(shifted, options, std::nullopt), key);
  RenderOptions tent = options;
  tent.filter.tentRadius = 2.0;
  EXPECT_NE(renderKey(d, tent, std::nullopt), key);
  // No tessellation named is `auto`, the renderer's default, and not a level.
  {
    SceneDescription named = d;
    ASSERT_EQ(named.shapes.size(), 1u);
    auto params = std::make_shared<MeshFileShapeParams>(*named.shapes[0].as<MeshFileShapeParams>());
    params->tessellation = "auto";
    named.shapes[0].params = params;
    EXPECT_EQ(renderKey(named, options, std::nullopt), key);
    params->tessellation = "8";
    EXPECT_NE(renderKey(named, options, std::nullopt), key);
  }
  // The mesh file's bytes count, not only its name.
  std::ofstream(dir / "tri.obj") << "v 0 0 0\nv 1 0 0\nv 0 1.5 0\nf 1 2 3\n";
  EXPECT_NE(renderKey(d, options, std::nullopt), key);

  RenderState state;
  state.key = key;
  state.width = 8;
  state.height = 8;
  EXPECT_NO_THROW(checkResumable(state, key, 8, 8, "s.state"));
  try {
    checkResumable(state, key + 1, 8, 8, "s.state");
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("s.state: the render state was saved by another render"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(checkResumable(state, key, 8, 9, "s.state"), Error);
  fs::remove_all(dir);
}

TEST(RenderKey, TheLoadersDigestsStandInForReadingTheMeshFilesAgain) {
  const fs::path dir = fs::temp_directory_path() / "quadtri_test_render_key_digests";
  fs::create_directories(dir);
  std::ofstream(dir / "tri.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  std::ofstream(dir / "scene.xml") << R"(<scene version="3.0.0">
  <sensor type="perspective">
    <float name="fov" value="40"/>
    <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
  </sensor>
  <shape type="obj"><string name="filename" value="tri.obj"/></shape>
</scene>
)";
  const SceneDescription d = loadSceneDescription(dir / "scene.xml");
  const BuiltScene built = buildScene(d);
  // The loader recorded the file it read: its bytes' FNV-1a and count.
  ASSERT_EQ(built.fileDigests.size(), 1u);
  const auto& [path, digest] = *built.fileDigests.begin();
  EXPECT_EQ(path, dir / "tri.obj");
  EXPECT_EQ(digest.bytes, 32u);
  EXPECT_EQ(digest.hash, FileDigest::of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").hash);
  RenderOptions options;
  options.samplesPerPixel = 4;
  // The same keys whether the file is read again or its digest is taken.
  const RenderKeys read = renderKeys(d, options, std::nullopt);
  const RenderKeys given = renderKeys(d, options, std::nullopt, &built.fileDigests);
  EXPECT_EQ(read.render, given.render);
  EXPECT_EQ(read.film, given.film);
  // With the digest given, the mesh file is not read at all.
  fs::remove(dir / "tri.obj");
  EXPECT_THROW(renderKeys(d, options, std::nullopt), Error);
  EXPECT_EQ(renderKeys(d, options, std::nullopt, &built.fileDigests).render, read.render);
  // Another digest is another render.
  FileDigests other = built.fileDigests;
  other.begin()->second.hash ^= 1;
  EXPECT_NE(renderKeys(d, options, std::nullopt, &other).render, read.render);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace quadtri
