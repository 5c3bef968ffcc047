// Bad geometry (README "Bad geometry"): what the loader removes, what it keeps and reports,
// what every model makes of the kept defects, and why crack_rate is then undefined.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "quadtri/analysis/metrics.h"
#include "quadtri/math/error.h"
#include "quadtri/mesh/mesh_io.h"
#include "quadtri/mesh/mesh_repair.h"
#include "quadtri/mesh/shapes.h"
#include "quadtri/mesh/topology.h"

namespace quadtri {
namespace {

class MeshRepair : public ::testing::Test {
 protected:
  std::filesystem::path dir;
  void SetUp() override {
    dir = std::filesystem::temp_directory_path() /
          ("quadtri-repair-" + std::to_string(::getpid()) + "-" +
           ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir);
  }
  void TearDown() override { std::filesystem::remove_all(dir); }
  std::filesystem::path write(const std::string& name, const std::string& text) {
    const std::filesystem::path p = dir / name;
    std::ofstream(p) << text;
    return p;
  }
};

// A unit square of two triangles (0 1 2, 0 2 3) in z = 0, normals +z, plus the damage.
const char* kSquare =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nvn 0 0 0\n"
    "f 1//1 2//1 3//1\nf 1//1 3//1 4//1\n";

TEST_F(MeshRepair, RemovesWhatNoModelCanUseAndCountsEachDefect) {
  const std::string damaged = std::string(kSquare) +
                              "v 0.5 0.5 1\nv 2 0 0\nv 3 0 0\n"
                              "f 1//1 2//1 3//1\n"   // duplicate
                              "f 3//1 2//1 1//1\n"   // duplicate, reversed
                              "f 1//1 1//1 2//1\n"   // collapsed: names vertex 1 twice
                              "f 1//1 3//1 5//1\n"   // a third triangle on edge 1-3
                              "f 2//1 6//1 7//1\n"   // zero area: three points on one line
                              "f 1//2 2//1 4//1\n";  // a zero normal, on a new triangle
  const TriangleMesh mesh = loadMesh(write("damaged.obj", damaged));
  const MeshRepairs& r = mesh.repairs;
  EXPECT_EQ(r.duplicateFaces, 2u);
  EXPECT_EQ(r.collapsedFaces, 1u);
  EXPECT_EQ(r.replacedNormals, 1u);
  EXPECT_EQ(r.zeroAreaFaces, 1u);
  // Edge 1-3 has three triangles; 1-2 has the square's, the zero-normal one and (removed) none
  // of the duplicates: 0 1 2, 0 1 3 → two; 1-4 is shared by 0 2 3 and 0 1 3.
  EXPECT_EQ(r.nonManifoldEdges, 1u);
  // 2 + 1 + 1 + 1 triangles stay: the square, the fin, the collinear one, the zero-normal one.
  EXPECT_EQ(mesh.triangleCount(), 5u);
  EXPECT_EQ(MeshTopology(mesh).nonManifoldEdgeCount(), 1u);
  // The replaced normal is the face normal of triangle 0 1 3 (+z).
  EXPECT_NEAR(mesh.cornerNormal(4, 0).z(), 1.0, 1e-12);
  EXPECT_EQ(r.summary(),
            "replaced 1 NaN, infinite or zero normal by its face normal; removed 1 triangle "
            "naming a vertex twice and 2 duplicate triangles; kept 1 zero-area triangle and 1 "
            "edge with three or more triangles (crack_rate is undefined)");
  const std::optional<std::string> w = repairWarning(mesh, "damaged.obj");
  ASSERT_TRUE(w);
  EXPECT_EQ(w->rfind("damaged.obj: replaced", 0), 0u) << *w;
}

TEST_F(MeshRepair, IsolatedVerticesAreRemovedAndTheRestRenumberedInOrder) {
  TriangleMesh mesh;
  mesh.positions = {Vec3(9, 9, 9), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(7, 7, 7), Vec3(0, 1, 0)};
  mesh.triangles = {{1, 2, 4}};
  const MeshRepairs did = repairMesh(mesh);
  EXPECT_EQ(did.isolatedVertices, 2u);
  ASSERT_EQ(mesh.positions.size(), 3u);
  EXPECT_EQ(mesh.positions[0], Vec3(0, 0, 0));
  EXPECT_EQ(mesh.positions[2], Vec3(0, 1, 0));
  EXPECT_EQ(mesh.triangles[0], (Tri{0, 1, 2}));
  EXPECT_EQ(mesh.repairs.summary(), "removed 2 isolated vertices");
}

TEST_F(MeshRepair, CleanMeshesAreLeftBitwiseUnchanged) {
  for (const char* spec : {"icosphere:2", "torus:1,0.35,24,12", "cube:2", "genus2:10"}) {
    TriangleMesh mesh = parseBuiltinSpec(spec)->mesh;
    const TriangleMesh before = mesh;
    const MeshRepairs did = repairMesh(mesh);
    EXPECT_FALSE(did.any()) << spec << ": " << did.summary();
    EXPECT_EQ(mesh.positions, before.positions) << spec;
    EXPECT_EQ(mesh.triangles, before.triangles) << spec;
    EXPECT_FALSE(repairWarning(mesh, spec)) << spec;
  }
}

// An OBJ of the mesh's positions and faces, without normals, with the faces whose index is in
// `flipped` written in the other winding.
std::string objOf(const TriangleMesh& mesh, const std::vector<size_t>& flipped) {
  std::string text;
  for (const Vec3& p : mesh.positions)
    text += "v " + std::to_string(p.x()) + " " + std::to_string(p.y()) + " " +
            std::to_string(p.z()) + "\n";
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    Tri f = mesh.triangles[t];
    if (std::find(flipped.begin(), flipped.end(), t) != flipped.end()) std::swap(f[1], f[2]);
    text += "f " + std::to_string(f[0] + 1) + " " + std::to_string(f[1] + 1) + " " +
            std::to_string(f[2] + 1) + "\n";
  }
  return text;
}

// Triangles whose face normal points away from the origin (the icosphere's outside).
size_t outward(const TriangleMesh& mesh) {
  size_t n = 0;
  for (size_t t = 0; t < mesh.triangleCount(); ++t)
    n += mesh.faceCross(t).dot(mesh.corner(t, 0) + mesh.corner(t, 1) + mesh.corner(t, 2)) > 0;
  return n;
}

TEST_F(MeshRepair, InconsistentWindingIsReWoundToMostOfItsPartsArea) {
  const TriangleMesh sphere = parseBuiltinSpec("icosphere:2")->mesh;  // 320 triangles, outward
  const size_t n = sphere.triangleCount();
  ASSERT_EQ(outward(sphere), n);
  std::vector<size_t> third, twoThirds;
  for (size_t t = 0; t < n; ++t) (t % 3 == 0 ? third : twoThirds).push_back(t);
  // A third wound inward: they are re-wound outward, the rest untouched.
  const TriangleMesh a = loadMesh(write("third.obj", objOf(sphere, third)));
  EXPECT_EQ(a.repairs.reorientedFaces, third.size());
  EXPECT_EQ(outward(a), n);
  // Two thirds inward: the part takes the inward winding of most of its area, consistently.
  const TriangleMesh b = loadMesh(write("two-thirds.obj", objOf(sphere, twoThirds)));
  EXPECT_EQ(b.repairs.reorientedFaces, third.size());
  EXPECT_EQ(outward(b), 0u);
  // Either way the normals are computed from the re-wound faces: every corner is consistent.
  for (const TriangleMesh* m : {&a, &b})
    for (size_t t = 0; t < m->triangleCount(); ++t)
      for (int k = 0; k < 3; ++k) EXPECT_GT(m->faceCross(t).dot(m->cornerNormal(t, k)), 0.0);
  const std::optional<std::string> w = repairWarning(a, "third.obj");
  ASSERT_TRUE(w);
  EXPECT_EQ(*w, "third.obj: re-wound 107 triangles to agree with their neighbours");
  // Consistently wound, whichever way: nothing to re-wind.
  const TriangleMesh c = loadMesh(write("all.obj", objOf(sphere, [&] {
                                          std::vector<size_t> all(n);
                                          for (size_t t = 0; t < n; ++t) all[t] = t;
                                          return all;
                                        }())));
  EXPECT_EQ(c.repairs.reorientedFaces, 0u);
  EXPECT_EQ(outward(c), 0u);
}

TEST_F(MeshRepair, FileNormalsKeepTheWindingAndAMobiusStripIsKeptAndReported) {
  // A square of two triangles wound against each other, with +z normals: the normals say which
  // side is out, so the second triangle stays an inconsistent corner for analyze to count.
  const TriangleMesh square = loadMesh(write("square.obj",
                                             "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\n"
                                             "f 1//1 2//1 3//1\nf 1//1 4//1 3//1\n"));
  EXPECT_EQ(square.repairs.reorientedFaces, 0u);
  EXPECT_EQ(square.triangles[1], (Tri{0, 3, 2}));
  // A Möbius strip of 12 quads: no winding is consistent, so it is left as wound.
  std::string strip;
  const int quads = 12;
  for (int i = 0; i < quads; ++i) {
    const double a = 2.0 * M_PI * i / quads, h = 0.3 * std::cos(a / 2), r = 0.3 * std::sin(a / 2);
    strip += "v " + std::to_string((1 + h) * std::cos(a)) + " " +
             std::to_string((1 + h) * std::sin(a)) + " " + std::to_string(r) + "\n";
    strip += "v " + std::to_string((1 - h) * std::cos(a)) + " " +
             std::to_string((1 - h) * std::sin(a)) + " " + std::to_string(-r) + "\n";
  }
  for (int i = 0; i < quads; ++i) {
    // Vertices 2i+1, 2i+2 (1-based) across the strip; the last quad joins them crossed.
    const int a0 = 2 * i + 1, a1 = 2 * i + 2;
    const int b0 = i + 1 < quads ? a0 + 2 : 2, b1 = i + 1 < quads ? a1 + 2 : 1;
    strip += "f " + std::to_string(a0) + " " + std::to_string(b0) + " " + std::to_string(b1) +
             "\nf " + std::to_string(a0) + " " + std::to_string(b1) + " " + std::to_string(a1) +
             "\n";
  }
  const TriangleMesh mobius = loadMesh(write("mobius.obj", strip));
  EXPECT_EQ(mobius.repairs.nonOrientableParts, 1u);
  EXPECT_EQ(mobius.repairs.reorientedFaces, 0u);
  EXPECT_NE(mobius.repairs.summary().find("kept 1 non-orientable part (as wound)"),
            std::string::npos)
      << mobius.repairs.summary();
}

TEST_F(MeshRepair, OnlyCollapsedTrianglesIsAClearError) {
  const auto p = write("collapsed.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 1 2\nf 2 3 3\n");
  try {
    loadMesh(p);
    FAIL() << "loaded a mesh without a surface";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("collapsed.obj"), std::string::npos) << e.what();
  }
}

TEST_F(MeshRepair, AnObjWithoutFacesSaysSo) {
  const auto p = write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  try {
    loadMesh(p);
    FAIL() << "loaded a mesh without faces";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("points.obj: the file holds no faces"), std::string::npos)
        << e.what();
  }
}

TEST_F(MeshRepair, APlyWithoutFacesSaysSo) {
  // A point cloud, as the corpus' b9.ply (an empty face element): read by Assimp, whose
  // post-processing drops the points and then says "all meshes are orphaned".
  const auto p = write("points.ply",
                       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                       "property float y\nproperty float z\nelement face 0\n"
                       "property list uchar int vertex_indices\nend_header\n"
                       "0 0 0\n1 0 0\n0 1 0\n");
  try {
    loadMesh(p);
    FAIL() << "loaded a mesh without faces";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("points.ply: no faces: 3 vertices"), std::string::npos)
        << e.what();
  }
}

TEST_F(MeshRepair, NonFiniteCoordinatesAreAnErrorNamingTheVertex) {
  TriangleMesh mesh;
  mesh.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, std::nan(""), 0)};
  mesh.triangles = {{0, 1, 2}};
  try {
    mesh.validate("arrays");
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "arrays: vertex 2 has a non-finite coordinate");
  }
}

// Every model converts a mesh with kept defects (a non-manifold edge and a zero-area
// triangle): finite metrics, corners on their vertices, and crack_rate undefined with its
// reason.
TEST_F(MeshRepair, EveryModelConvertsKeptDefectsAndCrackRateSaysWhyItIsUndefined) {
  TriangleMesh mesh = parseBuiltinSpec("icosphere:1")->mesh;
  const Tri f = mesh.triangles[0];
  const Vec3 a = mesh.positions[f[0]], b = mesh.positions[f[1]];
  mesh.positions.push_back(1.5 * (0.5 * (a + b)));  // a fin on edge f0-f1
  const uint32_t fin = uint32_t(mesh.positions.size() - 1);
  mesh.triangles.push_back({f[0], f[1], fin});
  mesh.normals.push_back(safeNormalized(mesh.faceCross(mesh.triangles.size() - 1)));
  const uint32_t n = uint32_t(mesh.normals.size() - 1);
  mesh.normalIndices.push_back({n, n, n});
  repairMesh(mesh);
  ASSERT_EQ(mesh.repairs.nonManifoldEdges, 1u);
  const auto shared = std::make_shared<const TriangleMesh>(mesh);
  AnalysisOptions options;
  options.crack.lines = 1000;
  for (const std::string& model : modelNames()) {
    const ModelMetrics m = analyzeNamedModel(model, shared, "fin", std::nullopt, options, {});
    EXPECT_TRUE(std::isfinite(m.vertexPositionError)) << model;
    EXPECT_TRUE(std::isfinite(m.vertexNormalErrorDeg)) << model;
    EXPECT_TRUE(std::isfinite(m.fallbackRate)) << model;
    if (model != "quadric-implicit" && model != "quadric-edges-eq42") {
      EXPECT_LT(m.vertexPositionError, 1e-9) << model;
    }
    EXPECT_FALSE(m.crackRate) << model;
    EXPECT_NE(m.crackRateUndefined.find("1 edge has three or more triangles"), std::string::npos)
        << model << ": " << m.crackRateUndefined;
  }
  // A closed mesh has a crack rate and no reason.
  const auto closed = std::make_shared<const TriangleMesh>(parseBuiltinSpec("icosphere:1")->mesh);
  const ModelMetrics m = analyzeNamedModel("flat", closed, "ico", std::nullopt, options, {});
  EXPECT_TRUE(m.crackRate);
  EXPECT_TRUE(m.crackRateUndefined.empty());
  const std::string table =
      metricsTable({analyzeNamedModel("flat", shared, "fin", std::nullopt, options, {})});
  EXPECT_NE(table.find("crack_rate: not defined: 1 edge has three or more triangles"),
            std::string::npos)
      << table;
}

}  // namespace
}  // namespace quadtri
