// Marching tetrahedra and the genus-2 pretzel: closed, manifold, oriented, on the surface.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "quadtri/math/error.h"
#include "quadtri/mesh/isosurface.h"
#include "quadtri/mesh/shapes.h"
#include "quadtri/mesh/topology.h"

namespace quadtri {
namespace {

ImplicitFunction unitSphere() {
  return {[](const Vec3& p) { return p.squaredNorm() - 1.0; },
          [](const Vec3& p) { return Vec3(2.0 * p); }};
}

// Every edge has two sides that run through it in opposite directions.
bool consistentlyOriented(const TriangleMesh& mesh, const MeshTopology& topo) {
  for (const Edge& e : topo.edges) {
    if (e.sides.size() != 2) return false;
    const auto [t0, k0] = e.sides[0];
    const auto [t1, k1] = e.sides[1];
    if (mesh.triangles[t0][k0] == mesh.triangles[t1][k1]) return false;
  }
  return true;
}

double signedVolume(const TriangleMesh& mesh) {
  double v = 0;
  for (size_t t = 0; t < mesh.triangleCount(); ++t)
    v += mesh.corner(t, 0).dot(mesh.corner(t, 1).cross(mesh.corner(t, 2))) / 6.0;
  return v;
}

long eulerCharacteristic(const TriangleMesh& mesh, const MeshTopology& topo) {
  return long(mesh.positions.size()) - long(topo.edges.size()) + long(mesh.triangleCount());
}

TEST(Isosurface, SphereIsClosedOrientedAndOnTheSurface) {
  const ImplicitFunction f = unitSphere();
  const TriangleMesh m = marchingTetrahedra(f, Vec3::Constant(-1.3), Vec3::Constant(1.27), 10);
  const MeshTopology topo(m);
  EXPECT_TRUE(topo.isClosed());
  EXPECT_TRUE(consistentlyOriented(m, topo));
  EXPECT_EQ(eulerCharacteristic(m, topo), 2);
  EXPECT_GT(signedVolume(m), 0.0);  // outward
  EXPECT_NEAR(signedVolume(m), 4.0 * kPi / 3.0, 0.1);
  for (const Vec3& p : m.positions) EXPECT_NEAR(p.norm(), 1.0, 1e-14);
}

TEST(Isosurface, NewtonProjectionLandsOnTheSurfaceAlongTheNormal) {
  const Vec3 q = projectOntoZeroSet(unitSphere(), Vec3(0.3, -0.2, 0.5));
  EXPECT_NEAR(q.norm(), 1.0, 1e-15);
  EXPECT_NEAR((q - Vec3(0.3, -0.2, 0.5).normalized()).norm(), 0.0, 1e-15);
  EXPECT_THROW(projectOntoZeroSet(unitSphere(), Vec3::Zero()), Error);  // ∇f = 0
}

TEST(Isosurface, RejectsASurfaceThatLeavesTheBox) {
  EXPECT_THROW(marchingTetrahedra(unitSphere(), Vec3::Constant(-0.9), Vec3::Constant(0.9), 6),
               Error);
  EXPECT_THROW(marchingTetrahedra(unitSphere(), Vec3::Constant(-2), Vec3::Constant(2), 0), Error);
}

TEST(Genus2, IsAClosedOrientedManifoldOfGenusTwoOnItsSurface) {
  const BuiltinMesh b = makeBuiltin("genus2");
  ASSERT_TRUE(b.truth);
  const MeshTopology topo(b.mesh);
  EXPECT_TRUE(topo.isClosed());
  EXPECT_TRUE(consistentlyOriented(b.mesh, topo));
  EXPECT_EQ(eulerCharacteristic(b.mesh, topo), -2);  // 2 − 2g with g = 2
  EXPECT_GT(signedVolume(b.mesh), 0.0);
  for (const Vec3& p : b.mesh.positions) EXPECT_LT(b.truth->distance(p), 1e-12);
  // Outward everywhere: each face agrees with the surface normal at its centroid.
  for (size_t t = 0; t < b.mesh.triangleCount(); ++t) {
    const Vec3 c = (b.mesh.corner(t, 0) + b.mesh.corner(t, 1) + b.mesh.corner(t, 2)) / 3.0;
    EXPECT_GT(b.mesh.faceNormal(t).dot(b.truth->normal(c)), 0.0) << "face " << t;
  }
  // The shading normals are the surface's.
  for (size_t t = 0; t < b.mesh.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR((b.mesh.cornerNormal(t, k) - b.truth->normal(b.mesh.corner(t, k))).norm(), 0.0,
                  1e-12);
}

TEST(Genus2, LooksLikeScannedData) {
  const BuiltinMesh b = makeBuiltin("genus2");
  const TriangleMesh& m = b.mesh;
  // Valences vary, as on a scan (a subdivided icosphere has only 5 and 6).
  std::map<uint32_t, int> valence;
  for (const Tri& t : m.triangles)
    for (uint32_t v : t) ++valence[v];
  int lo = 100, hi = 0;
  for (const auto& [v, n] : valence) {
    lo = std::min(lo, n);
    hi = std::max(hi, n);
  }
  EXPECT_LE(lo, 4);
  EXPECT_GE(hi, 8);
  // Near-slivers: some corner angles are tiny, but no triangle is degenerate.
  double minAngle = 180, minArea = kInfinity, meanArea = 0;
  for (size_t t = 0; t < m.triangleCount(); ++t) {
    for (int k = 0; k < 3; ++k)
      minAngle = std::min(minAngle, angleDegrees(m.corner(t, (k + 1) % 3) - m.corner(t, k),
                                                 m.corner(t, (k + 2) % 3) - m.corner(t, k)));
    minArea = std::min(minArea, m.faceCross(t).norm() / 2);
    meanArea += m.faceCross(t).norm() / 2 / double(m.triangleCount());
  }
  EXPECT_LT(minAngle, 5.0);
  EXPECT_GT(minArea, 1e-6 * meanArea);
  // Gauss–Bonnet holds exactly on a closed mesh: the angle defects sum to 2πχ = −4π, and the
  // saddles around the holes carry negative defects.
  std::vector<double> defect(m.positions.size(), 2 * kPi);
  for (size_t t = 0; t < m.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k)
      defect[m.triangles[t][k]] -= angleDegrees(m.corner(t, (k + 1) % 3) - m.corner(t, k),
                                                m.corner(t, (k + 2) % 3) - m.corner(t, k)) *
                                   kPi / 180;
  double total = 0, mostNegative = 0;
  for (double d : defect) {
    total += d;
    mostNegative = std::min(mostNegative, d);
  }
  EXPECT_NEAR(total, -4 * kPi, 1e-9);
  EXPECT_LT(mostNegative, -0.01);
}

TEST(Genus2, IsDeterministicAndRefinable) {
  const BuiltinMesh a = makeBuiltin("genus2"), b = makeBuiltin("genus2");
  EXPECT_EQ(a.mesh.positions, b.mesh.positions);
  EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
  const BuiltinMesh fine = *parseBuiltinSpec("genus2:80");
  const MeshTopology topo(fine.mesh);
  EXPECT_TRUE(topo.isClosed());
  EXPECT_EQ(eulerCharacteristic(fine.mesh, topo), -2);
  EXPECT_GT(fine.mesh.triangleCount(), 3 * a.mesh.triangleCount());
  EXPECT_THROW(parseBuiltinSpec("genus2:4"), Error);
  EXPECT_THROW(parseBuiltinSpec("genus2:16,2"), Error);
}

TEST(Genus2, DistanceIsTheOffsetAlongTheNormal) {
  const BuiltinMesh b = makeBuiltin("genus2");
  const AnalyticSurface& s = *b.truth;
  for (size_t i = 0; i < b.mesh.positions.size(); i += 97) {
    const Vec3& p = b.mesh.positions[i];
    const Vec3 n = s.normal(p);
    for (double d : {-1e-3, 1e-3, 1e-2})
      EXPECT_NEAR(s.distance(p + d * n), std::abs(d), 1e-9) << "vertex " << i;
  }
  // Its size is the half length: the tip (x, 0, 0) with x⁴ − x² = a lies on the surface.
  EXPECT_LT(s.distance(Vec3(s.size(), 0, 0)), 1e-14);
  // Measured even at the critical points of f, where the gradient vanishes: the centre sits
  // under the saddle's (0, 0, ±a).
  EXPECT_NEAR(s.distance(Vec3::Zero()), 0.2, 1e-9);
}

}  // namespace
}  // namespace quadtri
