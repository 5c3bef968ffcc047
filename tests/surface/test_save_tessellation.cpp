// A tessellated surface written block by block (saveTessellation) is the surface tessellate
// builds whole: the same OBJ bytes, and a PLY file whose vertices are its points in order.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "quadtri/math/error.h"
#include "quadtri/mesh/mesh_io.h"
#include "quadtri/mesh/shapes.h"
#include "quadtri/surface/model.h"
#include "quadtri/surface/tessellate.h"

namespace quadtri {
namespace {

namespace fs = std::filesystem;

std::string bytesOf(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

fs::path testDir() {
  const fs::path dir = fs::temp_directory_path() / "quadtri_test_save_tessellation";
  fs::create_directories(dir);
  return dir;
}

// The vertices (x y z nx ny nz as floats) and faces of a PLY file saveMesh's writers wrote.
struct Ply {
  std::vector<float> vertices;
  std::vector<Tri> faces;
};

Ply readPly(const std::string& bytes) {
  Ply ply;
  const size_t end = bytes.find("end_header\n");
  EXPECT_NE(end, std::string::npos);
  std::istringstream header(bytes.substr(0, end));
  size_t vertices = 0, faces = 0;
  for (std::string word; header >> word;)
    if (word == "element") {
      std::string name;
      size_t count = 0;
      header >> name >> count;
      (name == "vertex" ? vertices : faces) = count;
    }
  const char* p = bytes.data() + end + 11;
  ply.vertices.resize(6 * vertices);
  std::memcpy(ply.vertices.data(), p, ply.vertices.size() * sizeof(float));
  p += ply.vertices.size() * sizeof(float);
  ply.faces.resize(faces);
  for (Tri& f : ply.faces) {
    EXPECT_EQ(*p, 3);
    std::memcpy(f.data(), p + 1, sizeof(Tri));
    p += 1 + sizeof(Tri);
  }
  EXPECT_EQ(size_t(p - bytes.data()), bytes.size());
  return ply;
}

TEST(SaveTessellation, BlockByBlockIsTheWholeSurface) {
  // The torus has one normal per point and is streamed, in one block and in blocks of a few
  // patches; the cylinder's rims split normals, so a model that welds its points there builds
  // it whole and saveMesh writes it.
  struct Case {
    const char* spec;
    Tessellation tessellation;
    size_t blockPoints;
    bool streamed;
  };
  const std::vector<Case> cases = {
      {"torus:1,0.35,16,8", Tessellation{Tessellation::Kind::Lattice, 3}, size_t(1) << 20, true},
      {"torus:1,0.35,16,8", Tessellation{Tessellation::Kind::Lattice, 3}, 37, true},
      {"torus:1,0.35,6,4", Tessellation::thesis(), 3000, true},
      {"cylinder:12,3", Tessellation{Tessellation::Kind::Lattice, 2}, 40, false}};
  const fs::path dir = testDir();
  for (const Case& c : cases) {
    const auto mesh = std::make_shared<const TriangleMesh>(parseBuiltinSpec(c.spec)->mesh);
    for (const std::string& name : modelNames()) {
      SCOPED_TRACE(std::string(c.spec) + " " + name + " block " + std::to_string(c.blockPoints));
      const auto model = makeModel(name, mesh);
      const TriangleMesh whole = tessellate(*model, c.tessellation);
      for (const char* ext : {".obj", ".ply"}) {
        const fs::path streamed = dir / (std::string("streamed") + ext);
        const fs::path reference = dir / (std::string("whole") + ext);
        EXPECT_EQ(saveTessellation(*model, c.tessellation, streamed, c.blockPoints),
                  whole.triangleCount());
        saveMesh(whole, reference);
        const std::string got = bytesOf(streamed), want = bytesOf(reference);
        // The torus is streamed; so is the cylinder under a model that does not weld points.
        const bool tessellated = model->representation() != Representation::InputTriangles;
        const bool inPointOrder =
            std::string(ext) == ".ply" && tessellated && (c.streamed || !model->sharesEdges());
        if (!inPointOrder) {
          EXPECT_TRUE(got == want) << ext;
          continue;
        }
        // Vertex i is point i; the faces are the triangles.
        const Ply ply = readPly(got);
        ASSERT_EQ(ply.vertices.size(), 6 * whole.positions.size());
        ASSERT_EQ(whole.normals.size(), whole.positions.size());
        EXPECT_EQ(whole.normalIndices, whole.triangles);
        bool same = true;
        for (size_t i = 0; i < whole.positions.size(); ++i)
          for (int k = 0; k < 3; ++k)
            same = same && ply.vertices[6 * i + k] == float(whole.positions[i][k]) &&
                   ply.vertices[6 * i + 3 + k] == float(whole.normals[i][k]);
        EXPECT_TRUE(same);
        EXPECT_EQ(ply.faces, whole.triangles);
      }
    }
  }
}

TEST(SaveTessellation, BlocksThatDoNotHoldTheCountsWriteNothing) {
  const fs::path path = testDir() / "short.obj";
  fs::remove(path);
  MeshStream stream;
  stream.points = 3;
  stream.triangles = 1;
  stream.blocks = 1;
  stream.blockPoints = [](size_t, std::vector<Vec3>& p, std::vector<Vec3>& n) {
    p = {Vec3(0, 0, 0), Vec3(1, 0, 0)};
    n = {Vec3(0, 0, 1), Vec3(0, 0, 1)};
  };
  stream.blockTriangles = [](size_t, std::vector<Tri>& t) { t = {Tri{0, 1, 2}}; };
  EXPECT_THROW(saveMeshStream(stream, path), Error);
  EXPECT_FALSE(fs::exists(path));
  stream.blockPoints = [](size_t, std::vector<Vec3>& p, std::vector<Vec3>& n) {
    p = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, std::nan(""), 0)};
    n = {Vec3(0, 0, 1), Vec3(0, 0, 1), Vec3(0, 0, 1)};
  };
  EXPECT_THROW(saveMeshStream(stream, testDir() / "nan.ply"), Error);
  EXPECT_FALSE(fs::exists(testDir() / "nan.ply"));
}

}  // namespace
}  // namespace quadtri
