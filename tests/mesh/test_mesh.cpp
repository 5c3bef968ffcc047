#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <random>

#include "quadtri/math/error.h"
#include "quadtri/mesh/mesh_io.h"
#include "quadtri/mesh/normals.h"
#include "quadtri/mesh/shapes.h"
#include "quadtri/mesh/topology.h"

namespace quadtri {
namespace {

// The adjacency against a map from each undirected edge to its sides in half-edge order, on a
// random soup with repeated, degenerate (a == a) and non-manifold edges: edges numbered by their
// first side, sides in triangle order, edgeOf pointing back.
TEST(Topology, MatchesAMapOfEdgesOnARandomSoup) {
  std::mt19937 rng(7);
  TriangleMesh m;
  const uint32_t vertices = 40;
  for (uint32_t v = 0; v < vertices; ++v) m.positions.emplace_back(v, v * v % 7, v % 3);
  std::uniform_int_distribution<uint32_t> pick(0, vertices - 1);
  for (int t = 0; t < 400; ++t) m.triangles.push_back({pick(rng), pick(rng), pick(rng)});
  std::map<std::pair<uint32_t, uint32_t>, std::vector<EdgeSide>> reference;
  std::vector<std::pair<uint32_t, uint32_t>> firstSeen;
  for (uint32_t t = 0; t < m.triangles.size(); ++t)
    for (uint8_t k = 0; k < 3; ++k) {
      const uint32_t a = m.triangles[t][k], b = m.triangles[t][(k + 1) % 3];
      const auto key = std::minmax(a, b);
      auto& sides = reference[{key.first, key.second}];
      if (sides.empty()) firstSeen.emplace_back(key.first, key.second);
      sides.emplace_back(t, k);
    }
  const MeshTopology topo(m);
  ASSERT_EQ(topo.edges.size(), firstSeen.size());
  size_t nonManifold = 0;
  for (size_t e = 0; e < topo.edges.size(); ++e) {
    const Edge& edge = topo.edges[e];
    EXPECT_EQ(std::make_pair(edge.a, edge.b), firstSeen[e]) << e;
    const std::vector<EdgeSide>& sides = reference[firstSeen[e]];
    ASSERT_EQ(edge.sides.size(), sides.size()) << e;
    for (size_t i = 0; i < sides.size(); ++i) {
      EXPECT_EQ(edge.sides[i], sides[i]) << e;
      EXPECT_EQ(topo.edgeOf[sides[i].first][sides[i].second], e);
    }
    nonManifold += sides.size() > 2;
  }
  EXPECT_EQ(topo.nonManifoldEdgeCount(), nonManifold);
  EXPECT_GT(nonManifold, 0u);  // the soup does exercise shared edges
}

TEST(Topology, AnIndexPastTheVerticesIsAnError) {
  TriangleMesh m;
  m.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  m.triangles = {{0, 1, 2}, {2, 1, 3}};
  try {
    const MeshTopology topo(m);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("triangle 1: vertex index 3"), std::string::npos)
        << e.what();
  }
}

TEST(Shapes, PolyhedraAreClosedAndOnTheUnitSphere) {
  for (const char* name :
       {"tetrahedron", "icosahedron", "icosphere", "uv-sphere", "ellipsoid", "torus"}) {
    const BuiltinMesh b = makeBuiltin(name);
    MeshTopology topo(b.mesh);
    EXPECT_TRUE(topo.isClosed()) << name;
    // Euler characteristic: 2 for spheres, 0 for the torus.
    const long chi =
        long(b.mesh.positions.size()) - long(topo.edges.size()) + long(b.mesh.triangleCount());
    EXPECT_EQ(chi, std::string(name) == "torus" ? 0 : 2) << name;
    ASSERT_TRUE(b.truth);
    for (const Vec3& p : b.mesh.positions) EXPECT_LT(b.truth->distance(p), 1e-12) << name;
    // Outward orientation: every face normal agrees with the analytic normal at its centroid.
    for (size_t t = 0; t < b.mesh.triangleCount(); ++t) {
      const Vec3 c = (b.mesh.corner(t, 0) + b.mesh.corner(t, 1) + b.mesh.corner(t, 2)) / 3.0;
      EXPECT_GT(b.mesh.faceNormal(t).dot(b.truth->normal(c)), 0.0) << name << " face " << t;
    }
  }
}

TEST(Shapes, IcosphereTriangleCounts) {
  for (int level = 0; level <= 3; ++level) {
    ShapeParams p;
    p.level = level;
    EXPECT_EQ(makeBuiltin("icosphere", p).mesh.triangleCount(), size_t(20) << (2 * level));
  }
}

TEST(Shapes, AverageNormalsOfRegularPolyhedraAreRadial) {
  // Thesis eq. 2.8 on a regular polyhedron gives the circumscribed sphere's normal exactly.
  for (const char* name : {"tetrahedron", "icosahedron"}) {
    ShapeParams p;
    p.analyticNormals = false;
    const BuiltinMesh b = makeBuiltin(name, p);
    for (size_t t = 0; t < b.mesh.triangleCount(); ++t)
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR((b.mesh.cornerNormal(t, k) - b.mesh.corner(t, k).normalized()).norm(), 0.0,
                    1e-12);
  }
}

TEST(Shapes, EllipsoidDistanceMatchesSampledMinimum) {
  const AnalyticSurface e{AnalyticSurface::Kind::Ellipsoid, 1.0, 0.7, 0.5};
  const Vec3 queries[] = {Vec3(1.3, 0.2, -0.1), Vec3(0.1, 0.1, 0.1), Vec3(0, 0, 2),
                          Vec3(-0.4, 0.9, 0.3)};
  for (const Vec3& q : queries) {
    double best = kInfinity;
    for (int i = 0; i <= 400; ++i)
      for (int j = 0; j < 800; ++j) {
        const double th = kPi * i / 400, ph = 2 * kPi * j / 800;
        const Vec3 s(std::sin(th) * std::cos(ph), 0.7 * std::sin(th) * std::sin(ph),
                     0.5 * std::cos(th));
        best = std::min(best, (s - q).norm());
      }
    EXPECT_NEAR(e.distance(q), best, 2e-3) << q.transpose();
    EXPECT_LE(e.distance(q), best + 1e-9);
  }
}

TEST(Shapes, BuiltinSpecParsing) {
  EXPECT_EQ(parseBuiltinSpec("icosphere:2")->mesh.triangleCount(), 320u);
  EXPECT_EQ(parseBuiltinSpec("torus:1,0.25,12,6")->mesh.triangleCount(), 144u);
  EXPECT_FALSE(parseBuiltinSpec("no-such-shape"));
  EXPECT_THROW(parseBuiltinSpec("icosphere:x"), Error);
  EXPECT_THROW(parseBuiltinSpec("torus:0.2,1"), Error);
}

class MeshIo : public ::testing::Test {
 protected:
  // One folder per process and test: ctest runs tests as parallel processes, and a folder
  // shared between them would be removed under another test's feet.
  std::filesystem::path dir = std::filesystem::temp_directory_path() /
                              ("quadtri-test-" + std::to_string(::getpid()) + "-" +
                               ::testing::UnitTest::GetInstance()->current_test_info()->name());
  void SetUp() override { std::filesystem::create_directories(dir); }
  void TearDown() override { std::filesystem::remove_all(dir); }
};

TEST_F(MeshIo, ObjAndPlyRoundTripKeepPositionsNormalsAndAdjacency) {
  const BuiltinMesh b = makeBuiltin("icosphere");
  for (const char* ext : {".obj", ".ply"}) {
    const auto path = dir / (std::string("sphere") + ext);
    saveMesh(b.mesh, path);
    const TriangleMesh m = loadMesh(path);
    ASSERT_EQ(m.triangleCount(), b.mesh.triangleCount()) << ext;
    EXPECT_EQ(m.positions.size(), b.mesh.positions.size()) << ext;
    EXPECT_TRUE(MeshTopology(m).isClosed()) << ext;
    for (size_t t = 0; t < m.triangleCount(); ++t)
      for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR((m.corner(t, k) - b.mesh.corner(t, k)).norm(), 0.0, 1e-6);
        EXPECT_NEAR((m.cornerNormal(t, k) - b.mesh.cornerNormal(t, k)).norm(), 0.0, 1e-6);
      }
  }
}

TEST_F(MeshIo, SplitNormalsStaySplitWhilePositionsWeld) {
  // A cube-like crease: two triangles share an edge but carry different normals there.
  const auto path = dir / "crease.obj";
  std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                         "vn 0 0 -1\nvn -1 0 0\n"
                         "f 1//1 3//1 2//1\nf 1//2 4//2 3//2\n";
  const TriangleMesh m = loadMesh(path);
  EXPECT_EQ(m.positions.size(), 4u);
  ASSERT_EQ(m.triangleCount(), 2u);
  EXPECT_EQ(m.triangles[0][0], m.triangles[1][0]);  // welded vertex 1
  EXPECT_NEAR((m.cornerNormal(0, 0) - Vec3(0, 0, -1)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((m.cornerNormal(1, 0) - Vec3(-1, 0, 0)).norm(), 0.0, 1e-12);
}

TEST_F(MeshIo, MissingNormalsAreComputedAndBadInputNamesTheFile) {
  const auto path = dir / "plain.obj";
  std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const TriangleMesh m = loadMesh(path);
  EXPECT_NEAR((m.cornerNormal(0, 0) - Vec3(0, 0, 1)).norm(), 0.0, 1e-12);
  try {
    loadMesh(dir / "missing.obj");
    FAIL() << "no error for a missing file";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("missing.obj"), std::string::npos);
  }
  const auto bad = dir / "bad.txt";
  std::ofstream(bad) << "hello";
  EXPECT_THROW(loadMesh(bad), Error);
}

TEST_F(MeshIo, BadObjLinesAreReportedWithFileAndLine) {
  struct Case {
    const char* text;
    int line;
    const char* what;
  };
  const std::string head = "# a triangle\nv 0 0 0\nv 1 0 0\nv 0 1 0\n";  // lines 1-4
  const Case cases[] = {
      {"v 0 1 abc\nf 1 2 3\n", 5, "'abc' is not a finite number"},
      {"f 1 2 3\nv 0 1 abc\n", 6, "'abc' is not a finite number"},  // unused vertex
      {"v 0 1\n", 5, "has 2 values, expected x y z"},
      {"vn 0 0 nan\n", 5, "'nan' is not a finite number"},
      {"f 1 2 x\n", 5, "vertex index 'x' is not an integer"},
      {"f 1 2 3 foo\n", 5, "vertex index 'foo' is not an integer"},
      {"f 1 2\n", 5, "face has 2 vertices, expected at least 3"},
      {"f 1 2 4\nv 1 1 1\n", 5, "vertex index 4 is out of range, expected 1..3"},
      {"f 1 2 -4\n", 5, "vertex index -4 is out of range"},
      {"f 1 2 0\n", 5, "vertex index 0 is out of range"},
      {"f 1//1 2//1 3//1\n", 5, "normal index 1 is out of range, expected a normal defined"},
      {"vt 0 0\nf 1/1 2/2 3/1\n", 6, "texcoord index 2 is out of range, expected 1..1"},
      {"f 1/ 2 3\n", 5, "face vertex '1/' is malformed, expected i, i/j, i//k or i/j/k"},
      {"f 1/1/1/1 2 3\n", 5, "is malformed"},
  };
  const auto path = dir / "bad.obj";
  for (const Case& c : cases) {
    std::ofstream(path) << head << c.text;
    try {
      loadMesh(path);
      ADD_FAILURE() << "no error for: " << c.text;
    } catch (const Error& e) {
      const std::string message = e.what();
      const std::string where = path.string() + ":" + std::to_string(c.line) + ": ";
      EXPECT_EQ(message.rfind(where, 0), 0u) << message;
      EXPECT_NE(message.find(c.what), std::string::npos) << message;
    }
  }
}

TEST_F(MeshIo, ValidObjWithGroupsNegativeIndicesAndFullCornersLoads) {
  const auto path = dir / "quad.obj";
  std::ofstream(path) << "# two triangles and a quad\n"
                         "mtllib none.mtl\no square\ng top\ns 1\nusemtl plain\n"
                         "v 0 0 0\nv 1 0 0   # trailing comment\nv 1 1 0\n"
                         "v 0 1 0 1.0\n"
                         "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                         "vn 0 0 1\n"
                         "f 1/1/1 2/2/1 3/3/1\n"
                         "f -4/-4/-1 -2/-2/-1 -1/-1/-1\n"
                         "g side\n"
                         "v 0 0 -1\nv 1 0 -1\n"
                         "f 1//1 -1//1 -2//1 2//1\n"
                         "l 1 2\n";
  const TriangleMesh m = loadMesh(path);
  EXPECT_EQ(m.positions.size(), 6u);
  EXPECT_EQ(m.triangleCount(), 4u);  // two triangles plus the quad split in two
}

TEST(Normals, AngleWeightedDiffersFromAverageOnIrregularFan) {
  TriangleMesh m;
  m.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(-1, 0, 1)};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  computeVertexNormals(m, NormalSource::Average);
  const Vec3 avg = m.cornerNormal(0, 0);
  computeVertexNormals(m, NormalSource::Angle);
  const Vec3 ang = m.cornerNormal(0, 0);
  const Vec3 n1(0, 0, 1), n2 = Vec3(1, 0, 1).normalized();
  EXPECT_NEAR((avg - (n1 + n2).normalized()).norm(), 0.0, 1e-12);
  // Corner angles at vertex 0: 90° in the first face, the angle between +y and (-1,0,1) in
  // the second.
  const double a1 = kPi / 2, a2 = std::acos(Vec3(0, 1, 0).dot(Vec3(-1, 0, 1).normalized()));
  EXPECT_NEAR((ang - (a1 * n1 + a2 * n2).normalized()).norm(), 0.0, 1e-12);
}

}  // namespace
}  // namespace quadtri
