// `quadtri convert`/`analyze`/`render` on hostile mesh headers and over --max-memory: a clear
// error at once, a non-zero status and nothing written.
#include <gtest/gtest.h>

#include <fstream>

#include "cli/cli_runner.h"

namespace quadtri::test {
namespace {

namespace fs = std::filesystem;

template <typename T>
std::string bytesOf(const T& value) {
  return std::string(reinterpret_cast<const char*>(&value), sizeof(value));
}

// The hostile files of the issue: each header declares far more than its file holds.
std::vector<std::pair<std::string, std::string>> hostileFiles() {
  std::string plyBody;
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) plyBody += bytesOf(v);
  plyBody += '\3';
  for (int32_t i : {0, 1, 2}) plyBody += bytesOf(i);
  const uint32_t stlCount = 2147483649u;  // 84 + 50 n wraps to the file's size in 32 bits
  return {
      {"big.off", "OFF\n1000000000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"},
      {"big-ascii.ply",
       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
       "property float z\nelement face 2000000000\nproperty list uchar int vertex_indices\n"
       "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"},
      {"big-binary.ply",
       "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n"
       "property float y\nproperty float z\nelement face 1\nproperty list uchar int "
       "vertex_indices\nend_header\n" +
           plyBody},
      {"big.stl", std::string(80, '\0') + bytesOf(stlCount) + std::string(50, '\0')},
      {"index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 1000000000000\n"},
  };
}

// What each file's error must say besides its name.
const std::map<std::string, std::vector<std::string>> kExpected = {
    {"big.off", {"1000000000 vertices", "6000000002 bytes", "45 bytes"}},
    {"big-ascii.ply", {"2000000000 face", "4000000018 bytes", "26 bytes"}},
    {"big-binary.ply", {"4000000000 vertex", "48000000001 bytes", "49 bytes"}},
    {"big.stl", {"2147483649 triangles", "107374182534 bytes", "134 bytes"}},
    {"index.obj", {":4:", "1000000000000 is out of range", "expected 1..3"}},
    {"OutOfMemory.off", {"353535235358 vertices", "2121211412160 bytes", "309 bytes"}},
};

void expectRefused(CliProcess& p, const fs::path& dir, const fs::path& mesh,
                   const std::vector<std::string>& parts, const std::string& output) {
  EXPECT_EQ(p.wait(), 1) << p.stderrText();
  const std::string err = p.stderrText();
  EXPECT_NE(err.find("quadtri: error: " + mesh.string()), std::string::npos) << err;
  for (const std::string& part : parts)
    EXPECT_NE(err.find(part), std::string::npos) << part << " in " << err;
  // CPU time, not wall time: two cores shared by parallel tests make startup's wall time vary.
  EXPECT_LT(p.cpuSeconds(), 1.0) << mesh;
  if (!output.empty()) {
    EXPECT_FALSE(fs::exists(dir / output)) << output;
  }
  EXPECT_TRUE(temporaryFiles(dir).empty());
}

TEST(CliLimits, ConvertRefusesHostileHeadersAtOnceAndWritesNothing) {
  const fs::path dir = freshDir("limits");
  std::vector<std::pair<fs::path, std::string>> files;
  for (const auto& [name, bytes] : hostileFiles()) {
    std::ofstream(dir / name, std::ios::binary) << bytes;
    files.emplace_back(dir / name, name);
  }
  const fs::path assimp = "/usr/share/assimp/models/invalid/OutOfMemory.off";
  if (fs::exists(assimp)) files.emplace_back(assimp, "OutOfMemory.off");
  for (const auto& [path, name] : files) {
    SCOPED_TRACE(name);
    CliProcess p(
        {"convert", path.string(), "--model", "quadric-param", "-o", (dir / "out.obj").string()},
        dir);
    expectRefused(p, dir, path, kExpected.at(name), "out.obj");
  }
  // analyze refuses them the same way.
  CliProcess a({"analyze", (dir / "big.off").string(), "--model", "flat"}, dir, "analyze");
  expectRefused(a, dir, dir / "big.off", kExpected.at("big.off"), "");
  if (!fs::exists(assimp)) GTEST_SKIP() << assimp << " absent (Debian's assimp-testmodels)";
  fs::remove_all(dir);
}

TEST(CliLimits, MaxMemoryRefusesMeshesWhoseModelWouldNotFit) {
  const fs::path dir = freshDir("max-memory");
  // 2 triangles, tessellated at the thesis' 4802 triangles per patch: over 256 KiB.
  std::ofstream(dir / "quad.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
  CliProcess p(
      {"convert", (dir / "quad.obj").string(), "--model", "quadric-param", "--tessellation",
       "thesis", "--max-memory", "256K", "-o", (dir / "out.obj").string()},
      dir);
  expectRefused(p, dir, dir / "quad.obj",
                {"needs about", "building", "per triangle",
                 "over the --max-memory limit of "
                 "256 KiB"},
                "out.obj");
  // The same within a larger limit is written.
  CliProcess ok(
      {"convert", (dir / "quad.obj").string(), "--model", "quadric-param", "--tessellation",
       "thesis", "--max-memory", "1G", "-o", (dir / "out.obj").string()},
      dir, "ok");
  EXPECT_EQ(ok.wait(), 0) << ok.stderrText();
  EXPECT_TRUE(fs::exists(dir / "out.obj"));
  // An OBJ/PLY surface is streamed and charged so: 1,280 and 1,200 triangles at the thesis grid
  // (6 million triangles out) fit in 200 MiB (built whole they would need about 400 MB), the
  // cube's creases included, which give its edges' points two normals.
  for (const char* shape : {"icosphere:3", "cube:10"}) {
    CliProcess streamed({"convert", shape, "--model", "quadric-param", "--tessellation", "thesis",
                         "--max-memory", "200M", "-o", (dir / "streamed.ply").string()},
                        dir, shape);
    EXPECT_EQ(streamed.wait(), 0) << shape << ": " << streamed.stderrText();
  }
  // Built-in shapes: the model is charged before it is built.
  CliProcess shape({"convert", "icosphere:6", "--model", "quadric-param", "--max-memory", "64M",
                    "-o", (dir / "ico.obj").string()},
                   dir, "shape");
  expectRefused(shape, dir, "icosphere:6", {"81920 triangles", "64.0 MiB"}, "ico.obj");
  CliProcess bad({"convert", "icosahedron", "--model", "flat", "--max-memory", "lots", "-o",
                  (dir / "x.obj").string()},
                 dir, "bad");
  EXPECT_EQ(bad.wait(), 1);
  EXPECT_NE(bad.stderrText().find("--max-memory lots: expected a size"), std::string::npos)
      << bad.stderrText();
  fs::remove_all(dir);
}

// tri.obj (one triangle) and scene.xml rendering it at $res² pixels (default 64), 1 spp.
void writeTriangleScene(const fs::path& dir) {
  std::ofstream(dir / "tri.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  // The same triangle with normals that curve it.
  std::ofstream(dir / "curved.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn -0.3 -0.3 1\nvn 0.3 0 1\n"
                                       "vn 0 0.3 1\nf 1//1 2//2 3//3\n";
  std::ofstream(dir / "scene.xml") << R"(<scene version="3.0.0">
  <default name="res" value="64"/>
  <default name="mesh" value="tri.obj"/>
  <default name="tess" value="auto"/>
  <sensor type="perspective">
    <float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="$res"/><integer name="height" value="$res"/></film>
    <sampler type="independent"><integer name="sample_count" value="1"/></sampler>
  </sensor>
  <emitter type="constant"><rgb name="radiance" value="1, 1, 1"/></emitter>
  <shape type="obj">
    <string name="filename" value="$mesh"/><string name="tessellation" value="$tess"/>
  </shape>
</scene>
)";
}

TEST(CliLimits, RenderRefusesAnImageOrMeshOverMaxMemory) {
  const fs::path dir = freshDir("render-memory");
  writeTriangleScene(dir);
  // 32768² pixels (the most the film takes): 47 GiB of film, refused before it is allocated.
  CliProcess film({"render", (dir / "scene.xml").string(), "-D", "res=32768", "--max-memory", "1G",
                   "-o", (dir / "out.exr").string()},
                  dir, "film");
  EXPECT_EQ(film.wait(), 1);
  EXPECT_NE(film.stderrText().find("a 32768x32768 image needs about 47.0 GiB"), std::string::npos)
      << film.stderrText();
  EXPECT_LT(film.cpuSeconds(), 1.0);
  EXPECT_FALSE(fs::exists(dir / "out.exr"));
  // 32² pixels take 47 KiB; the triangle's quadric-param lattice of level 8 takes the rest.
  CliProcess mesh(
      {"render", (dir / "scene.xml").string(), "-D", "res=32", "-D", "tess=8", "--model",
       "quadric-param", "--max-memory", "50K", "-o", (dir / "out.exr").string()},
      dir, "mesh");
  EXPECT_EQ(mesh.wait(), 1);
  EXPECT_NE(mesh.stderrText().find("tri.obj: loading its 3 vertices"), std::string::npos)
      << mesh.stderrText();
  EXPECT_NE(mesh.stderrText().find("on top of the 47.0 KiB"), std::string::npos)
      << mesh.stderrText();
  EXPECT_FALSE(fs::exists(dir / "out.exr"));
  // With `auto` the mesh is charged at level 1 when it is loaded, and the level it picks
  // afterwards: 8 for the curved triangle, refused before its lattice is built; 1 for the flat
  // one, which fits.
  CliProcess curved(
      {"render", (dir / "scene.xml").string(), "-D", "res=32", "-D", "mesh=curved.obj", "--model",
       "quadric-param", "--max-memory", "50K", "-o", (dir / "out.exr").string()},
      dir, "curved");
  EXPECT_EQ(curved.wait(), 1);
  EXPECT_NE(curved.stderrText().find("(quadric-param): tessellating its 1 triangles at level 8 "
                                     "(auto) needs about 10."),
            std::string::npos)
      << curved.stderrText();
  EXPECT_FALSE(fs::exists(dir / "out.exr"));
  CliProcess flat({"render", (dir / "scene.xml").string(), "-D", "res=32", "--model",
                   "quadric-param", "--max-memory", "50K", "-o", (dir / "out.exr").string()},
                  dir, "flat");
  EXPECT_EQ(flat.wait(), 0) << flat.stderrText();
  EXPECT_TRUE(fs::exists(dir / "out.exr"));
  fs::remove(dir / "out.exr");
  EXPECT_TRUE(temporaryFiles(dir).empty());
  fs::remove_all(dir);
}

// Without its image module, render says where it looked and how to point at the module, exits
// 1 and writes nothing; commands that write no image (convert) do not need it.
TEST(CliLimits, RenderWithoutTheImageModuleSaysWhereItLookedAndWritesNothing) {
  const fs::path dir = freshDir("image-module");
  writeTriangleScene(dir);
  const fs::path missing = dir / "nowhere" / "libquadtri_image.so";
  ::setenv("QUADTRI_IMAGE_MODULE", missing.c_str(), 1);
  CliProcess render(
      {"render", (dir / "scene.xml").string(), "-D", "res=8", "-o", (dir / "out.png").string()},
      dir, "render");
  CliProcess convert({"convert", (dir / "tri.obj").string(), "--model", "quadric-param", "-o",
                      (dir / "tri.ply").string()},
                     dir, "convert");
  ::unsetenv("QUADTRI_IMAGE_MODULE");
  EXPECT_EQ(render.wait(), 1);
  const std::string err = render.stderrText();
  EXPECT_NE(err.find("cannot load quadtri's image module libquadtri_image.so"), std::string::npos)
      << err;
  EXPECT_NE(err.find(missing.string() + ": no such file"), std::string::npos) << err;
  EXPECT_NE(err.find("QUADTRI_IMAGE_MODULE"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir / "out.png"));
  // The convert runs beside the render: its own temporary file is gone once it has ended.
  EXPECT_EQ(convert.wait(), 0) << convert.stderrText();
  EXPECT_TRUE(temporaryFiles(dir).empty());
  EXPECT_TRUE(fs::exists(dir / "tri.ply"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace quadtri::test
