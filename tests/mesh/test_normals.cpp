// Crease-split angle-weighted normals (computeCreaseNormals) and the built-in shapes with
// creases (cube, cylinder).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "quadtri/math/error.h"
#include "quadtri/mesh/mesh_io.h"
#include "quadtri/mesh/normals.h"
#include "quadtri/mesh/shapes.h"
#include "quadtri/mesh/topology.h"

namespace quadtri {
namespace {

using VecKey = std::array<double, 3>;
VecKey key(const Vec3& v) {
  return {v.x(), v.y(), v.z()};
}

size_t distinctNormals(const TriangleMesh& m) {
  std::set<VecKey> s;
  for (size_t t = 0; t < m.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k) s.insert(key(m.cornerNormal(t, k)));
  return s.size();
}

// Distinct (vertex, normal) pairs over every corner: what a renderer must store per vertex.
size_t distinctCornerNormals(const TriangleMesh& m) {
  std::set<std::pair<uint32_t, VecKey>> s;
  for (size_t t = 0; t < m.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k) s.insert({m.triangles[t][k], key(m.cornerNormal(t, k))});
  return s.size();
}

TriangleMesh withoutNormals(TriangleMesh m) {
  m.normals.clear();
  m.normalIndices.clear();
  return m;
}

TEST(CreaseNormals, CubeSplitsAtThirtyDegreesAndNotAtOneEighty) {
  TriangleMesh cube = withoutNormals(makeBuiltin("cube").mesh);
  ASSERT_EQ(cube.positions.size(), 8u);
  computeCreaseNormals(cube, 30.0);
  // Three fans (faces) at each of the 8 corners.
  EXPECT_EQ(cube.normals.size(), 24u);
  EXPECT_EQ(distinctCornerNormals(cube), 24u);
  EXPECT_EQ(distinctNormals(cube), 6u);  // as vectors, the six face normals
  for (size_t t = 0; t < cube.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(cube.cornerNormal(t, k), cube.faceNormal(t));

  computeCreaseNormals(cube, 180.0);
  EXPECT_EQ(cube.normals.size(), 8u);
  EXPECT_EQ(distinctCornerNormals(cube), 8u);
  EXPECT_EQ(distinctNormals(cube), 8u);
  // Each face meets a corner with 90° in all (one right-angled triangle, or two 45° ones).
  for (size_t t = 0; t < cube.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR((cube.cornerNormal(t, k) - cube.corner(t, k).normalized()).norm(), 0.0, 1e-15);
  // Just above the cube's 90°, nothing splits; just below, everything does.
  computeCreaseNormals(cube, 90.0 + 1e-9);
  EXPECT_EQ(cube.normals.size(), 8u);
  computeCreaseNormals(cube, 90.0 - 1e-9);
  EXPECT_EQ(cube.normals.size(), 24u);
}

TEST(CreaseNormals, SubdividedFlatGridHasOneNormal) {
  // A 6×6 grid of squares in z = 0.25, cut along alternating diagonals, corners jittered in
  // the plane so corner angles differ: still one fan per vertex and one normal in all.
  TriangleMesh grid;
  const int n = 6;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const bool inner = i > 0 && j > 0 && i < n && j < n;
      const double jx = inner ? 0.13 * std::sin(3.1 * i + 1.7 * j) : 0.0;
      const double jy = inner ? 0.11 * std::cos(2.3 * i - 0.9 * j) : 0.0;
      grid.positions.emplace_back(i + jx, j + jy, 0.25);
    }
  auto id = [&](int i, int j) { return uint32_t(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const uint32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if ((i + j) % 2 == 0) {
        grid.triangles.push_back({a, b, c});
        grid.triangles.push_back({a, c, d});
      } else {
        grid.triangles.push_back({a, b, d});
        grid.triangles.push_back({b, c, d});
      }
    }
  for (const double crease : {0.0, 30.0, 180.0}) {
    computeCreaseNormals(grid, crease);
    EXPECT_EQ(grid.normals.size(), grid.positions.size()) << crease;
    EXPECT_EQ(distinctCornerNormals(grid), grid.positions.size()) << crease;
    EXPECT_EQ(distinctNormals(grid), 1u) << crease;
    EXPECT_EQ(grid.normals[0], Vec3(0, 0, 1)) << crease;
  }
}

TEST(CreaseNormals, SmoothIcosphereEqualsUnsplitAngleWeightedNormals) {
  // (Not genus2: its marching-tetrahedra slivers' face normals jump by more than 30°.)
  for (const char* spec : {"icosphere:3", "torus:1,0.35,32,16"}) {
    TriangleMesh split = withoutNormals(parseBuiltinSpec(spec)->mesh);
    TriangleMesh unsplit = split;
    computeCreaseNormals(split, 30.0);
    computeVertexNormals(unsplit, NormalSource::Angle);
    EXPECT_EQ(split.normals.size(), split.positions.size()) << spec;
    for (size_t t = 0; t < split.triangleCount(); ++t)
      for (int k = 0; k < 3; ++k)
        ASSERT_EQ(split.cornerNormal(t, k), unsplit.cornerNormal(t, k)) << spec;  // bit for bit
  }
}

TEST(CreaseNormals, IcosahedronSplitsBelowItsDihedralAngle) {
  // Neighbouring icosahedron faces' normals are 41.81° apart (180° − 138.19°).
  TriangleMesh ico = withoutNormals(makeBuiltin("icosahedron").mesh);
  computeCreaseNormals(ico, 41.0);
  EXPECT_EQ(ico.normals.size(), 60u);  // every corner its own fan: the face normals
  for (size_t t = 0; t < ico.triangleCount(); ++t)
    EXPECT_NEAR((ico.cornerNormal(t, 0) - ico.faceNormal(t)).norm(), 0.0, 1e-15);
  computeCreaseNormals(ico, 42.0);
  EXPECT_EQ(ico.normals.size(), 12u);
  for (size_t t = 0; t < ico.triangleCount(); ++t)
    EXPECT_NEAR((ico.cornerNormal(t, 0) - ico.corner(t, 0).normalized()).norm(), 0.0, 1e-15);
}

TEST(CreaseNormals, CylinderSplitsCapsFromTheSide) {
  // 24 segments: neighbouring side faces are 15° apart, caps meet the side at 90°.
  const BuiltinMesh b = parseBuiltinSpec("cylinder:24,3").value();
  TriangleMesh m = withoutNormals(b.mesh);
  computeCreaseNormals(m, 30.0);
  // One fan per side-only vertex and per cap centre, two per rim vertex.
  EXPECT_EQ(m.normals.size(), m.positions.size() + 2 * 24);
  for (size_t t = 0; t < m.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k) {
      // The side's angle-weighted normals are radial (each quad contributes 90° at each
      // corner); the caps' are axial.
      EXPECT_NEAR((m.cornerNormal(t, k) - b.mesh.cornerNormal(t, k)).norm(), 0.0, 1e-14);
    }
  // Below 15° the side splits into its columns of quads: two fans at a side vertex, three at a
  // rim vertex (left, right, cap), one at a cap centre.
  computeCreaseNormals(m, 10.0);
  EXPECT_EQ(m.normals.size(), 2u * 2 * 24 + 3 * 2 * 24 + 2);
}

TEST(CreaseNormals, BoundaryNonManifoldAndZeroAreaFacesEndFans) {
  // Three faces on the edge 0–1 (a fin), plus a zero-area face at vertex 0.
  TriangleMesh m;
  m.positions = {Vec3(0, 0, 0),      Vec3(1, 0, 0),   Vec3(0.5, 1, 0),
                 Vec3(0.5, -1, 0.1), Vec3(0.5, 0, 1), Vec3(2, 0, 0)};
  m.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}, {0, 5, 1}};
  computeCreaseNormals(m, 180.0);
  // No angle splits, but the non-manifold edge ends every fan: each face keeps its own corner
  // normals at vertices 0 and 1; the zero-area face (0, 5, 1 are collinear) carries the
  // unsplit angle-weighted normal.
  TriangleMesh unsplit = m;
  computeVertexNormals(unsplit, NormalSource::Angle);
  for (size_t t = 0; t < 3; ++t)
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR((m.cornerNormal(t, k) - m.faceNormal(t)).norm(), 0.0, 1e-15) << t;
  for (int k = 0; k < 3; ++k) EXPECT_EQ(m.cornerNormal(3, k), unsplit.cornerNormal(3, k));
  EXPECT_EQ(m.normals.size(), 12u);
}

TEST(CreaseNormals, InvariantUnderScaleAndRotation) {
  const TriangleMesh base = withoutNormals(parseBuiltinSpec("cylinder:16,2")->mesh);
  TriangleMesh ref = base;
  computeCreaseNormals(ref, 30.0);
  const Mat3 rotation = Eigen::AngleAxisd(0.9, Vec3(1, -2, 0.5).normalized()).toRotationMatrix();
  for (const double scale : {1e-6, 1.0, 1e6}) {
    TriangleMesh moved = base;
    for (Vec3& p : moved.positions) p = scale * (rotation * p) + Vec3(3, -1, 2) * scale;
    computeCreaseNormals(moved, 30.0);
    EXPECT_EQ(moved.normalIndices, ref.normalIndices) << scale;  // the same fans
    double worst = 0.0;
    for (size_t i = 0; i < ref.normals.size(); ++i)
      worst = std::max(worst, (rotation * ref.normals[i] - moved.normals[i]).norm());
    EXPECT_LT(worst, 1e-14) << scale;
  }
}

TEST(CreaseNormals, AngleOutsideZeroToOneEightyIsAnError) {
  TriangleMesh cube = makeBuiltin("cube").mesh;
  EXPECT_THROW(computeCreaseNormals(cube, -1.0), Error);
  EXPECT_THROW(computeCreaseNormals(cube, 180.5), Error);
  EXPECT_THROW(computeCreaseNormals(cube, std::nan("")), Error);
}

class CreaseNormalsIo : public ::testing::Test {
 protected:
  std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("quadtri_crease_" + std::to_string(::getpid()));
  void SetUp() override { std::filesystem::create_directories(dir); }
  void TearDown() override { std::filesystem::remove_all(dir); }
};

TEST_F(CreaseNormalsIo, FileWithoutNormalsGetsCreaseNormals) {
  const auto path = dir / "cube.obj";
  saveMesh(withoutNormals(makeBuiltin("cube").mesh), path);
  EXPECT_EQ(distinctCornerNormals(loadMesh(path)), 24u);  // default: split at 30°
  EXPECT_EQ(distinctCornerNormals(loadMesh(path, {NormalSource::File, 180.0})), 8u);
  const TriangleMesh average = loadMesh(path, NormalSource::Average);
  EXPECT_EQ(average.normals.size(), 8u);
  // Eq. 2.8 counts triangles, not angles: a corner where a face has two triangles leans
  // towards that face, away from the diagonal.
  double lean = 0.0;
  for (size_t t = 0; t < average.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k)
      lean = std::max(lean, angleDegrees(average.cornerNormal(t, k), average.corner(t, k)));
  EXPECT_GT(lean, 5.0);
  EXPECT_EQ(distinctCornerNormals(loadMeshSpec(path.string(), NormalSource::Angle).mesh), 24u);
  // A file with normals keeps them under File; Angle recomputes and splits them.
  const auto withNormals = dir / "smooth.obj";
  TriangleMesh smooth = makeBuiltin("cube").mesh;
  computeCreaseNormals(smooth, 180.0);
  saveMesh(smooth, withNormals);
  EXPECT_EQ(distinctCornerNormals(loadMesh(withNormals)), 8u);
  EXPECT_EQ(distinctCornerNormals(loadMesh(withNormals, {NormalSource::Angle, 30.0})), 24u);
}

TEST(CreaseShapes, CubeAndCylinderAreClosedOutwardAndOnTheirSurface) {
  for (const char* spec : {"cube", "cube:3", "cylinder", "cylinder:7,1"}) {
    const BuiltinMesh b = parseBuiltinSpec(spec).value();
    const MeshTopology topo(b.mesh);
    EXPECT_TRUE(topo.isClosed()) << spec;
    const long chi =
        long(b.mesh.positions.size()) - long(topo.edges.size()) + long(b.mesh.triangleCount());
    EXPECT_EQ(chi, 2) << spec;
    ASSERT_TRUE(b.truth);
    EXPECT_EQ(b.truth->size(), 1.0);
    for (const Vec3& p : b.mesh.positions) EXPECT_LT(b.truth->distance(p), 1e-15) << spec;
    for (size_t t = 0; t < b.mesh.triangleCount(); ++t) {
      const Vec3 c = (b.mesh.corner(t, 0) + b.mesh.corner(t, 1) + b.mesh.corner(t, 2)) / 3.0;
      const Vec3 n = b.truth->normal(c);
      EXPECT_GT(b.mesh.faceNormal(t).dot(n), 0.9) << spec << " face " << t;
      for (int k = 0; k < 3; ++k) {
        // Each corner carries its own face's or cap's normal, or the side's radial one.
        const Vec3 nk = b.mesh.cornerNormal(t, k);
        const Vec3& p = b.mesh.corner(t, k);
        if (b.truth->kind == AnalyticSurface::Kind::Box || std::abs(n.z()) == 1.0)
          EXPECT_EQ(nk, n) << spec;
        else
          EXPECT_NEAR((nk - Vec3(p.x(), p.y(), 0).normalized()).norm(), 0.0, 1e-15) << spec;
      }
    }
  }
  EXPECT_EQ(parseBuiltinSpec("cube:3")->mesh.triangleCount(), 6u * 2 * 9);
  EXPECT_EQ(parseBuiltinSpec("cube:3")->mesh.positions.size(), 56u);  // 4³ − 2³
  EXPECT_EQ(parseBuiltinSpec("cylinder:7,2")->mesh.triangleCount(), 2u * 7 * 2 + 2 * 7);
  EXPECT_EQ(makeBuiltin("cylinder").mesh.triangleCount(), 2u * 32 * 16 + 2 * 32);
  EXPECT_EQ(makeBuiltin("cube").mesh.normals.size(), 6u);
  EXPECT_THROW(parseBuiltinSpec("cube:0"), Error);
  EXPECT_THROW(parseBuiltinSpec("cube:2,3"), Error);
  EXPECT_THROW(parseBuiltinSpec("cylinder:2"), Error);
  EXPECT_THROW(parseBuiltinSpec("cylinder:8,0"), Error);
}

TEST(CreaseShapes, AverageNormalsAreUnsplit) {
  ShapeParams p;
  p.analyticNormals = false;
  const BuiltinMesh cube = makeBuiltin("cube", p);
  EXPECT_EQ(cube.mesh.normals.size(), 8u);
  const BuiltinMesh cylinder = makeBuiltin("cylinder", p);
  EXPECT_EQ(cylinder.mesh.normals.size(), cylinder.mesh.positions.size());
}

TEST(CreaseShapes, BoxAndCylinderDistances) {
  const AnalyticSurface box{AnalyticSurface::Kind::Box, 1, 2, 3};
  EXPECT_DOUBLE_EQ(box.distance(Vec3(2, 0, 0)), 1.0);
  EXPECT_NEAR(box.distance(Vec3(0.5, 0.5, 2.9)), 0.1, 1e-15);
  EXPECT_DOUBLE_EQ(box.distance(Vec3(0, 0, 0)), 1.0);
  EXPECT_DOUBLE_EQ(box.distance(Vec3(2, 3, 0)), std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(box.size(), 3.0);
  EXPECT_EQ(box.normal(Vec3(0.2, -1.9, 0.1)), Vec3(0, -1, 0));
  EXPECT_NEAR((box.normal(Vec3(2, 3, 0)) - Vec3(1, 1, 0).normalized()).norm(), 0.0, 1e-15);
  const AnalyticSurface cyl{AnalyticSurface::Kind::Cylinder, 1, 2, 0};
  EXPECT_DOUBLE_EQ(cyl.distance(Vec3(0, 0, 0)), 1.0);
  EXPECT_DOUBLE_EQ(cyl.distance(Vec3(0, 3, 0)), 2.0);
  EXPECT_DOUBLE_EQ(cyl.distance(Vec3(0, 0, -5)), 3.0);
  EXPECT_NEAR(cyl.distance(Vec3(0.3, 0.4, 1.75)), 0.25, 1e-15);
  EXPECT_DOUBLE_EQ(cyl.distance(Vec3(0, 2, 3)), std::sqrt(2.0));
  EXPECT_EQ(cyl.normal(Vec3(0, 0.5, -1.9)), Vec3(0, 0, -1));
  EXPECT_NEAR((cyl.normal(Vec3(0.6, 0.8, 0)) - Vec3(0.6, 0.8, 0)).norm(), 0.0, 1e-15);
}

}  // namespace
}  // namespace quadtri
