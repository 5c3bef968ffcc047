// A tessellated surface written block by block (saveTessellation) is the surface tessellate
// builds whole: the same OBJ bytes, and a PLY file whose vertices are its normals in order, each
// at its point.
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
  // The torus has one normal per point; the cylinder's rims give the points a model welds there
  // a normal on each side (extra normals after the points'), in one block and in blocks of a
  // few patches, at a lattice level and on the thesis grid.
  struct Case {
    const char* spec;
    Tessellation tessellation;
    size_t blockPoints;
  };
  const std::vector<Case> cases = {
      {"torus:1,0.35,16,8", Tessellation{Tessellation::Kind::Lattice, 3}, size_t(1) << 20},
      {"torus:1,0.35,16,8", Tessellation{Tessellation::Kind::Lattice, 3}, 37},
      {"torus:1,0.35,6,4", Tessellation::thesis(), 3000},
      {"cylinder:12,3", Tessellation{Tessellation::Kind::Lattice, 2}, 40},
      {"cylinder:12,3", Tessellation{Tessellation::Kind::Lattice, 4}, size_t(1) << 20},
      {"cylinder:6,2", Tessellation::thesis(), 6000}};
  const fs::path dir = testDir();
  bool someCrease = false;
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
        if (std::string(ext) == ".obj" ||
            model->representation() == Representation::InputTriangles) {
          EXPECT_TRUE(got == want) << ext;
          continue;
        }
        // A vertex per normal: normal v with its point's position (a point's own normal has
        // its number; an extra one is at the point whose corners name it); the faces' vertices
        // are their corners' normals.
        const size_t points = whole.positions.size();
        someCrease = someCrease || whole.normals.size() > points;
        std::vector<uint32_t> pointOf(whole.normals.size(), ~0u);
        for (size_t t = 0; t < whole.triangles.size(); ++t)
          for (int k = 0; k < 3; ++k) pointOf[whole.normalIndices[t][k]] = whole.triangles[t][k];
        const Ply ply = readPly(got);
        ASSERT_EQ(ply.vertices.size(), 6 * whole.normals.size());
        bool same = true;
        for (size_t v = 0; v < whole.normals.size(); ++v) {
          const size_t p = v < points ? v : pointOf[v];
          ASSERT_LT(p, points);
          for (int k = 0; k < 3; ++k)
            same = same && ply.vertices[6 * v + k] == float(whole.positions[p][k]) &&
                   ply.vertices[6 * v + 3 + k] == float(whole.normals[v][k]);
        }
        EXPECT_TRUE(same);
        EXPECT_EQ(ply.faces, whole.normalIndices);
      }
    }
  }
  EXPECT_TRUE(someCrease);  // the cylinder's rims did give extra normals
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
  stream.blockTriangles = [](size_t, std::vector<Tri>& t, std::vector<Tri>&) {
    t = {Tri{0, 1, 2}};
  };
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
