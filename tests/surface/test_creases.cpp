// Split normals never open a crack: every welded model builds each edge from data both sides
// share (creases.h, docs/DESIGN.md §11), measured on the capped cylinder and the cube.
#include <gtest/gtest.h>

#include <random>

#include "fixtures/sanitized.h"
#include "quadtri/analysis/crack_rate.h"
#include "quadtri/analysis/metrics.h"
#include "quadtri/geometry/model_geometry.h"
#include "quadtri/mesh/normals.h"
#include "quadtri/mesh/shapes.h"
#include "quadtri/mesh/topology.h"
#include "quadtri/surface/creases.h"
#include "quadtri/surface/edge_curves.h"
#include "quadtri/surface/tessellate.h"
#include "surface/surface_fixtures.h"

namespace quadtri {
namespace {

using test::edgeUv;

// The models whose render geometry is welded along shared edges.
const char* const kWelded[] = {"quadric-edges", "quadric-param", "phong", "pn",
                               "nagata",        "shading-offset"};
// The curved ones among them (shading-offset draws the input triangles).
const char* const kCurved[] = {"quadric-edges", "quadric-param", "phong", "pn", "nagata"};

std::shared_ptr<const TriangleMesh> shared(TriangleMesh mesh) {
  return std::make_shared<const TriangleMesh>(std::move(mesh));
}

// Max distance, relative to the mesh's box diagonal, between the two sides' points of every
// two-sided edge at 17 parameters.
double sharedEdgeGap(const SurfaceModel& model) {
  const TriangleMesh& mesh = model.mesh();
  const MeshTopology topo(mesh);
  const double size = mesh.bounds().diagonal().norm();
  double worst = 0.0;
  for (const Edge& edge : topo.edges) {
    if (edge.sides.size() != 2) continue;
    const auto [ta, ka] = edge.sides[0];
    const auto [tb, kb] = edge.sides[1];
    const bool aForward = mesh.triangles[ta][ka] == edge.a;
    const bool bForward = mesh.triangles[tb][kb] == edge.a;
    for (int i = 0; i <= 16; ++i) {
      const double s = i / 16.0;
      const Vec2 uva = edgeUv(ka, aForward ? s : 1.0 - s);
      const Vec2 uvb = edgeUv(kb, bForward ? s : 1.0 - s);
      const Vec3 pa = model.evaluate(ta, uva.x(), uva.y()).position;
      const Vec3 pb = model.evaluate(tb, uvb.x(), uvb.y()).position;
      worst = std::max(worst, (pa - pb).norm() / size);
    }
  }
  return worst;
}

CrackRateOptions lines(size_t count, uint64_t seed) {
  CrackRateOptions o;
  o.lines = count;
  o.seed = seed;
  return o;
}

TEST(Creases, WeldedModelsDoNotCrackOnTheCylinderAndTheCube) {
  // Before the crease treatment phong, pn and nagata cracked here (about 0.5% of lines).
  for (const char* spec : {"cylinder", "cube", "cube:3"}) {
    const auto mesh = shared(parseBuiltinSpec(spec)->mesh);
    ASSERT_TRUE(MeshTopology(*mesh).isClosed());
    for (const char* name : kWelded) {
      const auto model = makeModel(name, mesh);
      EXPECT_TRUE(model->sharesEdges()) << name;
      EXPECT_LT(sharedEdgeGap(*model), 1e-15) << name << " " << spec;
      const ModelGeometry g = modelGeometry(*model, Tessellation{});
      EXPECT_EQ(crackRate(g, lines(fixtures::samples(200000), 11)), 0.0) << name << " " << spec;
      if (g.triangles.triangleCount() > 0) {
        EXPECT_TRUE(MeshTopology(g.triangles).isClosed()) << name << " " << spec;
      }
    }
  }
}

TEST(Creases, AngleWeightedCreaseNormalsDoNotCrackEither) {
  // The same shapes with the normals a file without normals gets (split at 30°), and a shape
  // whose creases are not axis-aligned: the icosahedron split at 30° (every edge a crease).
  for (const char* spec : {"cylinder:20,3", "cube:2", "icosahedron"}) {
    TriangleMesh m = parseBuiltinSpec(spec)->mesh;
    computeCreaseNormals(m, 30.0);
    const auto mesh = shared(std::move(m));
    for (const char* name : kWelded) {
      const auto model = makeModel(name, mesh);
      EXPECT_LT(sharedEdgeGap(*model), 1e-15) << name << " " << spec;
      EXPECT_EQ(
          crackRate(modelGeometry(*model, Tessellation{}), lines(fixtures::samples(50000), 3)), 0.0)
          << name << " " << spec;
    }
  }
}

TEST(Creases, StraightCreasesStayStraight) {
  // Split face normals on the cube: every crease is a straight edge and every face flat, so
  // each curved model reproduces the cube itself.
  const BuiltinMesh cube = parseBuiltinSpec("cube:2").value();
  const auto mesh = shared(cube.mesh);
  for (const char* name : kCurved) {
    const auto model = makeModel(name, mesh);
    EXPECT_LT(truthDistance(*model, *cube.truth, 8), 1e-15) << name;
    // The geometric normal is the face normal everywhere.
    for (size_t t = 0; t < mesh->triangleCount(); ++t)
      EXPECT_NEAR((model->evaluate(t, 0.3, 0.3).normal - mesh->faceNormal(t)).norm(), 0.0, 1e-12)
          << name;
  }
}

TEST(Creases, CylinderRimFollowsTheCircleTangents) {
  const int segments = 24;
  const BuiltinMesh cylinder = parseBuiltinSpec("cylinder:24,2").value();
  const auto mesh = shared(cylinder.mesh);
  const double half = kPi / segments;  // half the angle an edge of the rim spans
  const MeshTopology topo(*mesh);
  for (const char* name : kCurved) {
    const auto model = makeModel(name, mesh);
    for (const Edge& edge : topo.edges) {
      const Vec3& a = mesh->positions[edge.a];
      const Vec3& b = mesh->positions[edge.b];
      if (a.z() != 1.0 || b.z() != 1.0 || a.head<2>().norm() < 0.5 || b.head<2>().norm() < 0.5)
        continue;  // not a rim edge
      for (auto [t, k] : edge.sides)
        for (int i = 0; i <= 8; ++i) {
          const Vec2 uv = edgeUv(k, i / 8.0);
          const Vec3 p = model->evaluate(t, uv.x(), uv.y()).position;
          EXPECT_NEAR(p.z(), 1.0, 1e-15) << name;  // the rim stays in the cap's plane
          if (i == 4 && std::string(name) != "phong" && std::string(name) != "pn") {
            // The quadratic whose control point is where the circle's tangents at a and b meet
            // (radius 1/cos(half)): its midpoint has radius (cos(half) + 1/cos(half))/2.
            EXPECT_NEAR(std::hypot(p.x(), p.y()), 0.5 * (std::cos(half) + 1.0 / std::cos(half)),
                        1e-14)
                << name;
          }
          if (i == 4 && std::string(name) == "pn") {
            // The cubic whose end tangents lie along the circle, each a third of the chord's
            // projection onto it.
            const double c = std::cos(2 * half), s = std::sin(2 * half);
            // a = (1, 0), b = (c, s); b1 = a + (s/3)(0, 1), b2 = b − (s/3)(−s, c).
            const double mx = (1 + 3 * 1 + 3 * (c + s * s / 3) + c) / 8;
            const double my = (0 + 3 * (s / 3) + 3 * (s - s * c / 3) + s) / 8;
            EXPECT_NEAR(std::hypot(p.x(), p.y()), std::hypot(mx, my), 1e-14) << name;
          }
        }
    }
    // Smooth normals where the models promise them: the geometric normal at every corner is
    // the corner's own (split) normal, crease corners included.
    if (std::string(name) == "phong") continue;
    const Vec2 corners[] = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)};
    double worst = 0.0;
    for (size_t t = 0; t < mesh->triangleCount(); ++t)
      for (int k = 0; k < 3; ++k)
        worst =
            std::max(worst, angleDegrees(model->evaluate(t, corners[k].x(), corners[k].y()).normal,
                                         mesh->cornerNormal(t, k)));
    EXPECT_LT(worst, 1e-9) << name;
    EXPECT_LT(truthDistance(*model, *cylinder.truth, 8), 0.004) << name;
  }
}

TEST(Creases, CreaseControlPointIsSymmetricBoundedAndExactWhereLinesMeet) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> coord(-1.0, 1.0);
  auto randomUnit = [&] { return Vec3(coord(rng), coord(rng), coord(rng)).normalized(); };
  for (int trial = 0; trial < 2000; ++trial) {
    const Vec3 va(coord(rng), coord(rng), coord(rng)), vb(coord(rng), coord(rng), coord(rng));
    EdgeEnd ea, eb;
    ea.kind = EdgeEnd::Kind::Crease;
    ea.direction = randomUnit();
    if (trial % 2) {
      eb.kind = EdgeEnd::Kind::Crease;
      eb.direction = randomUnit();
    }
    const Vec3 na = randomUnit(), nb = randomUnit();
    const Vec3 b1 = creaseControlPoint(va, ea, na, vb, eb, nb);
    const Vec3 b2 = creaseControlPoint(vb, eb, nb, va, ea, na);
    EXPECT_EQ(b1, b2);  // bit for bit, whichever side asks
    EXPECT_LE((b1 - 0.5 * (va + vb)).norm(), 0.5 * (vb - va).norm() * (1 + 1e-15));
    // Scale invariance.
    const double scale = 1e6;
    const Vec3 bs = creaseControlPoint(scale * va, ea, na, scale * vb, eb, nb);
    EXPECT_NEAR((bs / scale - b1).norm(), 0.0, 1e-9);
  }
  // Two tangent lines in a plane meet: b is their intersection.
  const Vec3 va(0, 0, 0), vb(2, 0, 0), apex(0.7, 0.9, 0);
  EdgeEnd ea, eb;
  ea.kind = eb.kind = EdgeEnd::Kind::Crease;
  ea.direction = apex.normalized();
  eb.direction = -(apex - vb).normalized();
  EXPECT_NEAR((creaseControlPoint(va, ea, Vec3::Zero(), vb, eb, Vec3::Zero()) - apex).norm(), 0.0,
              1e-14);
  // A crease line and a tangent plane: b is where the line meets the plane.
  EdgeEnd smooth;
  const Vec3 n = Vec3(0.868, 1.325, 0.4).normalized();  // plane through vb
  const Vec3 hit = va + ((vb - va).dot(n) / ea.direction.dot(n)) * ea.direction;
  ASSERT_LT((hit - Vec3(1, 0, 0)).norm(), 1.0);
  ASSERT_LT(std::abs(hit.x() - 1.0), 0.5);
  EXPECT_NEAR((creaseControlPoint(va, ea, Vec3::Zero(), vb, smooth, n) - hit).norm(), 0.0, 1e-14);
  // Where they meet at an end (a degenerate tangent), the Hermite fallback instead.
  const Vec3 through = Vec3(0, 0.3, 1).normalized();  // a plane through vb that contains va
  const Vec3 fallback = Vec3(1, 0, 0) + 0.25 * (ea.tangentPart(vb - va, Vec3::Zero()) -
                                                smooth.tangentPart(vb - va, through));
  EXPECT_EQ(creaseControlPoint(vb, smooth, through, va, ea, Vec3::Zero()), fallback);
  // A straight crease (a cube's edge): the midpoint exactly.
  ea.direction = eb.direction = Vec3(1, 0, 0);
  EXPECT_EQ(creaseControlPoint(va, ea, Vec3::Zero(), vb, eb, Vec3::Zero()), Vec3(1, 0, 0));
}

TEST(Creases, EndsAreSharedWithoutClassifyingWhereEveryVertexHasOneNormal) {
  // A mesh whose corners take one normal index per vertex has no end but Shared, and edgeEnds
  // says so without building the edge adjacency; a zero normal there, which each side replaces
  // by its own face normal, or a corner with a normal of its own, still gets its ends classified.
  TriangleMesh smooth = parseBuiltinSpec("icosphere:2")->mesh;
  ASSERT_EQ(smooth.normalIndices, smooth.triangles);
  {
    const TriangleMesh fresh = smooth;
    EXPECT_FALSE(edgeEndsNeedTopology(fresh));
    EXPECT_FALSE(edgeEnds(fresh).anySplit());
    EXPECT_EQ(fresh.topologyCache.builds(), 0u);
    TriangleMesh bare = smooth;  // no shading normals: nothing to split either
    bare.normals.clear();
    bare.normalIndices.clear();
    EXPECT_FALSE(edgeEndsNeedTopology(bare));
  }
  TriangleMesh zero = smooth;
  zero.normals[zero.triangles[0][0]] = Vec3::Zero();
  EXPECT_TRUE(edgeEndsNeedTopology(zero));
  const EdgeEnds zeroEnds = edgeEnds(zero);
  ASSERT_TRUE(zeroEnds.anySplit());
  EXPECT_EQ(zeroEnds[0][0][0].kind, EdgeEnd::Kind::Crease);
  TriangleMesh own = smooth;  // corner (0, 0) gets a tilted normal of its own
  own.normals.push_back((own.normals[own.normalIndices[0][0]] + Vec3(0.3, 0, 0)).normalized());
  own.normalIndices[0][0] = uint32_t(own.normals.size() - 1);
  EXPECT_TRUE(edgeEndsNeedTopology(own));
  EXPECT_TRUE(edgeEnds(own).anySplit());
  // The same normal under two indices is still one normal: classified, and Shared.
  TriangleMesh copied = smooth;
  copied.normals.push_back(copied.normals[copied.normalIndices[0][0]]);
  copied.normalIndices[0][0] = uint32_t(copied.normals.size() - 1);
  EXPECT_FALSE(edgeEnds(copied).anySplit());
  EXPECT_EQ(copied.topologyCache.builds(), 1u);
}

TEST(Creases, RandomSplitNormalsShareEveryEdge) {
  // Every corner of an icosphere gets its own random normal (within 50° of the sphere's), so
  // every edge end is split, most of them creases with directions far off the edge: each model
  // still builds one curve per edge, bounded and finite.
  std::mt19937_64 rng(17);
  TriangleMesh m = parseBuiltinSpec("icosphere:1")->mesh;
  m.normals.clear();
  for (size_t t = 0; t < m.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k) {
      m.normals.push_back(test::randomInCone(rng, m.corner(t, k).normalized(), 50.0));
      m.normalIndices[t][k] = uint32_t(m.normals.size() - 1);
    }
  const auto mesh = shared(std::move(m));
  // The largest distance from the unit sphere over a lattice of every patch.
  auto deviation = [&](const SurfaceModel& model) {
    double worst = 0.0;
    for (size_t t = 0; t < mesh->triangleCount(); ++t)
      for (int i = 0; i <= 8; ++i)
        for (int j = 0; i + j <= 8; ++j) {
          const SurfacePoint sp = model.evaluate(t, i / 8.0, j / 8.0);
          EXPECT_TRUE(allFinite(sp.position) && allFinite(sp.normal)) << model.name();
          worst = std::max(worst, std::abs(sp.position.norm() - 1.0));
        }
    return worst;
  };
  const double flat = deviation(*makeModel("flat", mesh));
  for (const char* name : kCurved) {
    const auto model = makeModel(name, mesh);
    EXPECT_LT(sharedEdgeGap(*model), 1e-15) << name;
    // No curve flung away: a control point within half the chord of its midpoint keeps the
    // edge within a quarter of the edge length of it.
    EXPECT_LT(deviation(*model), flat + 0.25 * mesh->meanEdgeLength()) << name;
    EXPECT_EQ(crackRate(modelGeometry(*model, Tessellation{}), lines(20000, 9)), 0.0) << name;
  }
}

TEST(Creases, TessellationKeepsEachSidesNormalAtCreases) {
  const auto mesh = shared(parseBuiltinSpec("cube")->mesh);
  for (const char* name : kCurved) {
    const auto model = makeModel(name, mesh);
    const TriangleMesh tess = tessellate(*model, {Tessellation::Kind::Lattice, 4});
    EXPECT_TRUE(MeshTopology(tess).isClosed()) << name;
    // Every tessellated triangle lies on one cube face and carries that face's normal at all
    // three corners, at the cube's edges and corners too.
    for (size_t t = 0; t < tess.triangleCount(); ++t)
      for (int k = 0; k < 3; ++k)
        ASSERT_NEAR((tess.cornerNormal(t, k) - tess.faceNormal(t)).norm(), 0.0, 1e-12) << name;
    // The welded points: 6·15 per face of a level-4 lattice on a 2-triangle face, shared.
    EXPECT_EQ(tess.positions.size(), 6u * 25 - 12 * 3 - 8 * 2) << name;
  }
  // A smooth mesh keeps one normal per tessellation vertex.
  const auto sphere = shared(parseBuiltinSpec("icosphere:1")->mesh);
  const TriangleMesh tess = tessellate(*makeModel("pn", sphere), {Tessellation::Kind::Lattice, 4});
  EXPECT_EQ(tess.normalIndices, tess.triangles);
}

TEST(Creases, InvariantUnderSimilarityTransformsWithSplitNormals) {
  const auto base = shared(parseBuiltinSpec("cylinder:9,2")->mesh);
  const Mat3 rotation = Eigen::AngleAxisd(0.7, Vec3(1, 2, -0.5).normalized()).toRotationMatrix();
  for (double scale : {1e-6, 1.0, 1e6}) {
    const Vec3 shift = scale * Vec3(3.0, -2.0, 5.0);
    TriangleMesh moved = *base;
    for (Vec3& p : moved.positions) p = scale * (rotation * p) + shift;
    for (Vec3& n : moved.normals) n = rotation * n;
    const auto mesh = shared(moved);
    for (const char* name : kCurved) {
      const auto a = makeModel(name, base);
      const auto b = makeModel(name, mesh);
      double posErr = 0.0, normErr = 0.0;
      for (size_t t = 0; t < base->triangleCount(); ++t)
        for (int i = 0; i <= 4; ++i)
          for (int j = 0; i + j <= 4; ++j) {
            const SurfacePoint pa = a->evaluate(t, i / 4.0, j / 4.0);
            const SurfacePoint pb = b->evaluate(t, i / 4.0, j / 4.0);
            posErr = std::max(
                posErr, (scale * (rotation * pa.position) + shift - pb.position).norm() / scale);
            normErr = std::max(normErr, (rotation * pa.normal - pb.normal).norm());
          }
      EXPECT_LT(posErr, 1e-11) << name << " scale " << scale;
      EXPECT_LT(normErr, 1e-9) << name << " scale " << scale;
    }
  }
}

}  // namespace
}  // namespace quadtri
